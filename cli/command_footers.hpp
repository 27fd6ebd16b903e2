// The --help footers of score, compare, search, simulate and design (long teaching text kept out of
// the command files so each stays parse -> call -> render).
#pragma once

namespace pinmask::cli {

inline constexpr const char* kScoreFooter =
    "Metrics (--metrics, comma-separated):\n"
    "  sidelobes  torus autocorrelation of the pattern: peak_autocorrelation (= K), max_sidelobe,\n"
    "             mean_sidelobe, integrated_sidelobe_level (sum of squared sidelobes / peak^2),\n"
    "             peak_to_sidelobe_ratio\n"
    "  spectrum   min_abs_pattern_spectrum (min |P^| over k != 0), spectral_flatness (geometric /\n"
    "             arithmetic mean of |P^|^2 over k != 0; 1 = flat), open_fraction, light_gain "
    "(K),\n"
    "             otf_condition_number (max/min |A^| where |K^| >= 0.1 max |K^|), spectral_zero\n"
    "             (|P^(k)| < 1e-3 sqrt(K) where the kernel passes light: the frequency, or null)\n"
    "  analytic   expected Wiener PSNR in closed form over one period, per noise level:\n"
    "             analytic_wiener_psnr_db_snrS (the --nsr filter), analytic_wiener_nsr_snrS,\n"
    "             analytic_optimal_wiener_psnr_db_snrS (per-frequency optimal filter bound).\n"
    "             Prior: --prior (default 16 natural 1/f textures, seeds 1000..1015; the same\n"
    "             prior in score, compare and search)\n"
    "  wiener     simulated: wiener_psnr_db_snrS, wiener_ssim_snrS, wiener_nsr_snrS (mean over\n"
    "             scenes; per_scene in --json)\n"
    "  tv         simulated TV-L2: tv_psnr_db_snrS, tv_ssim_snrS, tv_lambda_snrS (slow; opt-in)\n"
    "  depth      how well one capture tells the distance u of a point source on the axis "
    "(opt-in;\n"
    "             needs --photons): the Cramer-Rao bound sigma_u from the Fisher information of\n"
    "             the exact-geometry PSF's change with 1/u under Poisson + read noise, at 3\n"
    "             distances equally spaced in 1/u over --depth-from .. --depth-to (default: the\n"
    "             working distance / 2 .. x 2): depth_crb_rel_phP (worst sigma_u / u),\n"
    "             depth_axial_fwhm_m_phP (worst 2.355 sigma_u, metres), "
    "depth_worst_distance_m_phP\n"
    "             (where), depth_from_m, depth_to_m. The point source is one scene pixel of value\n"
    "             1: P K electrons in all. Lower is better\n"
    "Noise levels: --snr S (keys ...snrS): Gaussian, sigma^2 = mean(capture^2) / 10^(S/10) (the\n"
    "analytic error takes the prior's expected mean(capture^2)); or --photons P (keys ...phP):\n"
    "Poisson shot noise of P K electrons per pixel for a uniform scene of value 1 (K pinholes),\n"
    "plus read noise, dark current, saturation, ADC and film leak from the sensor flags, the\n"
    "expected dark offset removed (see pinmask simulate --help).\n"
    "Simulation: one period, cyclic model, capture = scene (*) PSF + noise; PSNR = 10 log10(1 /\n"
    "MSE) for scenes in [0, 1];\n"
    "SSIM: 11 x 11 Gaussian window (sigma 1.5), valid region. 'tuned' weights minimise the mean\n"
    "MSE over scenes and seeds by golden section on log10 (1e-7..10). Infinite values (a PSR with\n"
    "no sidelobes, a condition number with a spectral zero) are null in --json, inf in the table.\n"
    "Examples: pinmask score a.mask.json b.mask.json --scenes letter-R,usaf,natural --snr 20,30 "
    "--metrics sidelobes,spectrum,analytic,wiener --nsr tuned --json\n"
    "  pinmask score a.mask.json --photons 100,1000 --read-noise 3 --metrics analytic,wiener\n"
    "  pinmask score a.mask.json --photons 1000 --metrics analytic,depth --depth-from 0.4 "
    "--depth-to 2";

inline constexpr const char* kCompareFooter =
    "Table columns (also --json keys): K holes; n grid; spacing ok (spacing_ok); max SL "
    "(max_sidelobe) and PSR (peak_to_sidelobe_ratio) of the torus autocorrelation; min|P^| and "
    "flatness of the pattern DFT; zero (spectral_zero: a pattern frequency with |P^| < 1e-3 "
    "sqrt(K) where the kernel passes light); OTF cond over the kernel passband; analytic W "
    "(analytic_wiener_psnr_db): closed-form expected Wiener PSNR; sim W / sim TV: simulated "
    "one-period captures of --scenes decoded by Wiener and TV-L2, means over scenes. The table "
    "shows the first noise level; --json has every level under score's keys "
    "(analytic_wiener_psnr_db_snr30, wiener_psnr_db_ph2, ...): the numbers pinmask score prints "
    "for the same settings. Infinite values are null in --json.\n"
    "--baselines adds: the median of --baseline-count random valid masks with the first mask's "
    "n, K, spacing, tiles, camera and PSF settings (draw i seeded with --seed + i, ranked by "
    "simulated Wiener PSNR at the first level); the paper-like geometry (16 x 16, K 20); a MURA "
    "of the largest prime p = 4m + 1 <= n (breaks the spacing rule).\n"
    "Rules: every mask must be for the first mask's camera (exit 2 otherwise). --report r.pdf "
    "writes one PDF; r.svg or r.png write r-1.svg ... (one per page); r.config.json beside them, "
    "all or nothing.\n"
    "Example: pinmask compare a.mask.json b.mask.json --baselines --photons 2 --read-noise 3 "
    "--report report.pdf";

inline constexpr const char* kSearchFooter =

    "Writes rank-1.mask.json ... (provenance: seed, strategy, scores), run-log.csv (best "
    "objective at fixed evaluation counts), timing.csv (wall clock), summary.md and "
    "search.config.json, all or nothing. With --evals, masks, run-log.csv, summary.md and "
    "search.config.json are byte-identical run to run. Ctrl-C (or SIGTERM) stops and writes "
    "the best so far; a second signal only hurries it. While the run lasts, "
    "best-so-far.mask.json holds the best pattern found so far (under mpirun: rank 0's chains "
    "and what the cluster exchanged with it), rewritten when it improves, at most every 2 s, "
    "and at once on the first signal; the end removes it, so it is left only by a run that was "
    "killed (a second Ctrl-C to mpirun kills the ranks). PINMASK_TIME_LIMIT does not apply: "
    "--time is search's budget.\n"
    "Example: pinmask search --preset paper --grid 16 --holes 20 --time 20s --seed 1 --top 5 "
    "-o runs/a/\n"
    "Dim light, the pinhole count chosen: pinmask search --grid 32 --photons 3 --read-noise 3 "
    "--holes 5..40 --time 30s -o runs/dim/ (at this light the search beats random masks by "
    "0.9 dB on real photographs with a 32 x 32 grid, 0.5 dB with 16 x 16: docs/benchmarks.md, "
    "Choosing K at "
    "dim light; pinmask sweep varies \"grid\" to compare grids)\n"
    "Repeat a run (byte-identical masks with --evals) or vary it: pinmask search --config "
    "runs/a/search.config.json --seed 2 -o runs/b/";

// --robust (score, compare, search) and what its figures mean (optimize/metrics/robust_wiener.hpp).
inline constexpr const char* kRobustFlagHelp =
    "Fabrication errors, e.g. size=5um,jitter=2um,missing=0.01 (any subset): pinhole side bias "
    "+-size (both signs), position jitter sigma on the mask, probability a pinhole is missing; "
    "adds the expected analytic Wiener PSNR under them beside the nominal one (see below)";
inline constexpr const char* kRobustFooter =
    "Robust figures (--robust): the expected score under fabrication errors is the analytic "
    "Wiener MSE averaged over fabricated copies of the mask, each decoded with the NOMINAL "
    "(design) PSF, as an uncalibrated camera would: every pinhole side d + size or d - size "
    "(both signs averaged; the kernel of that side, brightness normalised), each pinhole centre "
    "moved by independent Gaussian jitter (sigma on the mask; sub-pixel moves area-resampled), "
    "each pinhole missing with the given probability; same prior, noise variance and filter "
    "(and NSR) as the nominal figure. Closed form (no sampling); no errors give exactly the "
    "nominal figure. Keys robust_wiener_psnr_db_snrS and robust_loss_db_snrS (nominal - robust); "
    "table column R.";

inline constexpr const char* kSimulateFooter =
    "Model: the cyclic forward model over one period (docs/design.md section 2): capture = "
    "scene (*) "
    "PSF, circular convolution with the PSF centred as `pinmask decode` expects, so decoding "
    "the capture with the mask returns the scene unshifted. --full-sensor repeats the period "
    "over the sensor: the periodic extension of the one-period capture, which is exact for the "
    "cyclic model; the period sits where the decoder's centred crop takes it. Noise is drawn per "
    "sensor pixel.\n"
    "Units: a uniform noiseless scene of value v gives v. Photon model: electrons / (N K), K the "
    "pinholes, plus a background (film leak + dark current) that the dark frame removes: "
    "`pinmask decode capture.tiff --dark dark.tiff ...`.\n"
    "Files: the capture (-o: .tif/.tiff float32, .png 16-bit clipped to [0, 1], .npy float32), "
    "OUT.config.json (the resolved configuration: mask, kernel, scene, noise, seed, tiling, "
    "units), and the dark frame when asked. All appear together or none does.\n"
    "Examples:\n"
    "  pinmask simulate m.mask.json --scene usaf --snr 30 -o capture.tiff\n"
    "  pinmask simulate m.mask.json --scene natural --photons 500 --read-noise 3 "
    "--dark-current 10 --optical-density 2 --full-sensor --dark-frame dark.tiff "
    "-o capture.tiff --explain";

inline constexpr const char* kDesignFooter =
    "Every figure is at the working distance u (--object-distance; a point source at u: "
    "1/z_eff = 1/f - 1/f' + 1/u): pitch, whole pixels per cell N, PSF size n N, periods on the "
    "sensor, LSI mismatch against N; the indented \"u = inf\" lines are the distant-object "
    "values the paper quotes. A solved pinhole (--solve pinhole, --pixels-per-cell) lands on the "
    "fabrication grid (--fab-grid, or the --vendor preset's, default 1nm) and the table says how "
    "far that moves the pitch at u. --json prints one object with unit-suffixed keys (_m = "
    "metres, _px = pixels): keys without a suffix and \"_at_u\" keys are at u, \"_at_inf\" "
    "keys at u = inf; infinite values are null, with the reason under \"notes\". The kernel row "
    "is the kernel psf would build at N px per cell over the band (--bandwidth: a Gaussian of "
    "that FWHM at 13 wavelengths), with the energy its support keeps; its warnings are psf's.\n"
    "Examples:\n"
    "  pinmask design --preset paper\n"
    "  pinmask design --lens-focal 55mm --object-distance inf --json   (f = f': Fraunhofer)\n"
    "  pinmask design --pixel-pitch 3.45um --sensor 2448x2048 --lens-focal 25mm \\\n"
    "      --sensor-distance 20mm --object-distance 2m --wavelength 530nm --pixels-per-cell 21\n"
    "      (solves d = 345 um for 21 whole pixels per cell at 2 m)\n"
    "  pinmask design --wavelength 850nm --bandwidth 30nm   (an LED's 30 nm band around 850 nm)";

}  // namespace pinmask::cli
