// The --help footer of `pinmask sweep` (teaching text kept out of cli/cmd_sweep.cpp).
#pragma once

namespace pinmask::cli {

inline constexpr const char* kSweepFooter =
    "SWEEP.json: a base search configuration (the keys of a search.config.json; see pinmask\n"
    "search --help) and the design points, as a grid (the Cartesian product, keys in\n"
    "alphabetical order, the last varying fastest) or as a list of points. Any search key may\n"
    "vary, by its dotted path: holes, grid, seed, strategy, optics.pinhole_m, noise.snr_db,\n"
    "noise.photons_per_pinhole, prior.family, weights.max_sidelobe, ... Example:\n"
    "  {\"format\": \"pinmask-sweep\", \"version\": 1,\n"
    "   \"base\": {\"grid\": 12, \"evaluations_per_chain\": 2000, \"rerank_scenes\": [],\n"
    "            \"noise\": {\"model\": \"photon\", \"photons_per_pinhole\": 100}},\n"
    "   \"grid\": {\"holes\": [8, 12, 16], \"noise.photons_per_pinhole\": [10, 100, 1000]}}\n"
    "or \"points\": [{\"holes\": 8}, {\"holes\": 16, \"seed\": 2}] instead of \"grid\".\n"
    "Rules: every point needs evaluations_per_chain >= 1 (no \"time\": points are reproducible);\n"
    "threads defaults to 1 per point; varying optics.* needs the whole base \"optics\" object "
    "(copy\n"
    "it from a search.config.json); noise.snr_db is Gaussian-only, photons_per_pinhole and the\n"
    "sensor keys photon-only. A bad file (unknown key, empty grid, incompatible values) is exit\n"
    "2 naming the key, before any search starts.\n"
    "MPI: mpirun -n N pinmask sweep ... shares the points among the ranks by a dynamic work queue\n"
    "(rank 0 hands out points and runs points too; results return as bytes); rank 0 alone\n"
    "writes. The files do not depend on the rank count or on scheduling: each point's result\n"
    "depends on its own configuration (its seed included) only.\n"
    "Writes into -o: sweep.csv and sweep.md (one row per point), points/point-NNNN.mask.json\n"
    "(the best mask) and points/point-NNNN.search.config.json (repeat a point with pinmask search\n"
    "--config), sweep.config.json, and psnr-vs-holes, psnr-vs-pinhole-size, psnr-vs-light (.svg\n"
    "and .png) for the axes the sweep varies. All or nothing. PINMASK_TIME_LIMIT does not\n"
    "apply: the points' evaluations_per_chain are the sweep's budget.\n"
    "Example: pinmask sweep sweep.json -o runs/sweep/   (mpirun -n 4 pinmask sweep ... on MPI)";

}  // namespace pinmask::cli
