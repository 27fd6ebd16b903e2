# Type stub of the pinmask module (python/*.cpp). Units are SI (metres, seconds) unless a name
# says otherwise. tests/python/test_stub_readme.py checks that every public name of the module is
# here, tests/python/test_stub_signatures.py every parameter, default and return type.
from os import PathLike
from typing import Any, Callable, Iterable, Literal, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

__version__: str

FloatArray = npt.NDArray[np.float64]
ArrayLike = npt.ArrayLike
Length = Union[float, str]  # metres, or a string with a unit: "440um", "55mm", "6m", "inf"
PathLikeStr = Union[str, PathLike[str]]
MaskLike = Union["Mask", PathLikeStr]
Levels = Union[float, Sequence[float]]  # one noise level or a list (score's keys per level)
Prior = Union[str, Sequence[PathLikeStr]]  # natural | text | stars, or image files

class Result(dict[str, Any]):
    """A function's result: a dict whose keys also read as attributes (r.image is r["image"]);
    nested dicts are Results too. to_dict() gives plain dicts and lists all the way down."""

    def __getattr__(self, name: str) -> Any: ...
    def to_dict(self) -> dict[str, Any]: ...

class Camera:
    object_distance_m: float  # u, +inf: distant object
    lens_focal_m: float  # f', +inf: no lens
    sensor_distance_m: float  # f
    wavelength_m: float  # the centre of the band
    bandwidth_m: float  # FWHM of the spectrum, 0: one wavelength
    pixel_pitch_m: float  # w
    pinhole_m: float  # d = cell side
    sensor_cols: int
    sensor_rows: int
    def __init__(
        self,
        object_distance_m: Length = 6.0,
        lens_focal_m: Optional[Length] = None,
        sensor_distance_m: Optional[Length] = None,
        wavelength_m: Optional[Length] = None,
        pixel_pitch_m: Optional[Length] = None,
        pinhole_m: Optional[Length] = None,
        sensor_cols: int = 720,
        sensor_rows: int = 480,
        bandwidth_m: Length = 0.0,
    ) -> None: ...
    def validate(self) -> None: ...
    def to_json(self) -> str: ...
    def __eq__(self, other: object) -> bool: ...

def load_camera(path: PathLikeStr) -> Camera: ...
def save_camera(camera: Camera, path: PathLikeStr) -> None: ...
def paper_camera() -> Camera: ...
def optics(
    camera: Optional[Camera] = None,
    grid: int = 16,
    holes: int = 20,
    tiles: int = 2,
    kernel: str = "auto",
    lsi_tolerance_px: float = 1.0,
    pixels_per_cell: Optional[int] = None,  # solve d for N whole pixels per cell at u
    solve: Optional[Literal["pinhole"]] = None,  # N = the nearest whole number at u
    fab_grid: Optional[Length] = None,  # the solved d lands on this grid (default 1 nm)
    vendor: Optional[str] = None,  # ... or on this export preset's grid
    spacing: float = 2.0,  # cells: reports the packing bound on holes
    save_camera: Optional[PathLikeStr] = None,  # write the camera reported (as --save-camera)
) -> Result: ...
def kernel_models() -> list[str]: ...
def choose_kernel_model(fresnel_number: float) -> tuple[str, str]: ...

class Pattern:
    n: int
    pinholes: list[tuple[int, int]]  # (row, col)
    tiles_rows: int
    tiles_cols: int
    min_spacing_cells: float
    def __init__(
        self,
        n: int = 16,
        pinholes: Sequence[tuple[int, int]] = (),
        tiles_rows: int = 2,
        tiles_cols: int = 2,
        min_spacing_cells: float = 2.0,
    ) -> None: ...
    def occupancy(self) -> npt.NDArray[np.uint8]: ...
    def spacing_violations(self) -> list[tuple[tuple[int, int], tuple[int, int], float]]: ...
    def validate(self, allow_spacing_violations: bool = False) -> None: ...

class Mask:
    pattern: Pattern
    camera: Camera
    pixels_per_cell: int
    kernel: str
    kernel_path: str
    wavelengths: list[tuple[float, float]]
    seed: int
    generator: str
    family: str
    spacing_violations_allowed: bool
    scores: dict[str, float]
    objective_figure: str
    def __init__(self) -> None: ...
    def geometry_hash(self) -> str: ...
    def to_json(self) -> str: ...
    def save(self, path: PathLikeStr) -> None: ...

def load_mask(path: PathLikeStr, allow_spacing_violations: bool = False) -> Mask: ...
def save_mask(mask: Mask, path: PathLikeStr) -> None: ...
def mask_from_json(text: str, allow_spacing_violations: bool = False) -> Mask: ...
def generate(
    family: Literal["random", "paper", "mura"] = "random",
    grid: Optional[int] = None,
    holes: Optional[int] = None,
    tiles: Optional[int] = None,
    spacing: Optional[float] = None,
    seed: int = 1,
    attempts: int = 20,
    allow_violations: bool = False,
    camera: Optional[Camera] = None,
    kernel: str = "auto",
    kernel_path: str = "",
    pixels_per_cell: Optional[int] = None,
) -> Mask: ...

class Kernel:
    @property
    def values(self) -> FloatArray: ...  # a writable view of the kernel's buffer
    origin_row: int
    origin_col: int
    @property
    def model(self) -> str: ...
    model_reason: str
    enclosed_energy: float
    support_capped: bool
    wavelengths: list[tuple[float, float]]

def kernel(mask: Mask, energy_fraction: float = 0.999) -> Kernel: ...
def psf(
    mask: Mask,
    kernel: Optional[str] = None,
    kernel_path: str = "",
    energy_fraction: float = 0.999,
    geometry: Literal["integer", "exact"] = "integer",
    object_distance: Optional[Length] = None,  # exact: default the mask's u
    size: Optional[tuple[int, int]] = None,  # exact: (rows, cols), default the sensor
) -> FloatArray: ...
def write_psf(
    mask: Mask,
    path: PathLikeStr,
    npy: bool = False,
    mask_file: str = "",
    kernel: Optional[str] = None,
    kernel_path: str = "",
    energy_fraction: float = 0.999,
) -> list[str]: ...
def read_psf(path: PathLikeStr) -> tuple[FloatArray, Optional[Result]]: ...
def read_image(
    path: PathLikeStr,
    bayer: Optional[Literal["sum2x2", "green", "g", "r", "b"]] = None,  # None: RAW as sum2x2
) -> tuple[FloatArray, float]: ...
def write_image(
    path: PathLikeStr,
    image: ArrayLike,
    scale: Union[Literal["max"], float, None] = None,  # PNG only: decode's --scale
    bits: Literal[8, 16] = 16,  # PNG only: decode's --bits (decode's default is 8)
) -> None: ...
def scene_names() -> list[str]: ...
def scene(name: str, rows: int, cols: int, seed: int = 0, alpha: float = 1.0) -> FloatArray: ...
def simulate(
    mask: MaskLike,
    scene: Union[str, ArrayLike] = "letter-R",
    snr_db: Optional[float] = None,
    photons: Optional[float] = None,
    read_noise: Optional[float] = None,
    dark_current: Optional[float] = None,
    full_well: Optional[float] = None,
    bits: Optional[int] = None,
    optical_density: Optional[float] = None,
    full_sensor: bool = False,
    sensor: Optional[tuple[int, int]] = None,
    dark_frame: bool = False,
    seed: int = 1,
    allow_violations: bool = False,
    precision: Literal["auto", "single", "double"] = "auto",
    geometry: Literal["integer", "exact"] = "integer",
    object_distance: Optional[Length] = None,  # exact: default the mask's u
    size: Optional[tuple[int, int]] = None,  # exact: (rows, cols), default the sensor
    threads: int = 0,  # FFTW threads for >= 512 x 512 (0: all cores)
) -> Result: ...
def decode(
    capture: ArrayLike,
    psf: Optional[ArrayLike] = None,
    mask: Optional[MaskLike] = None,
    method: Literal["auto", "wiener", "tikhonov", "tv", "tvqc", "richardson-lucy"] = "auto",
    model: Literal["auto", "cyclic", "linear"] = "auto",
    nsr: Union[None, float, Literal["auto"]] = None,
    lambda_: Union[None, float, Literal["auto"]] = None,
    regulariser: Optional[Literal["identity", "gradient"]] = None,
    eps: Optional[float] = None,
    noise_sigma: Optional[float] = None,
    nonneg: Optional[bool] = None,
    iters: Optional[int] = None,
    tol: Optional[float] = None,
    crop: Union[str, tuple[int, int]] = "auto",  # auto | center | none | (row, col)
    dark: Optional[ArrayLike] = None,
    background: Union[None, float, Literal["auto", "none", "corner"]] = "auto",
    downsample: int = 0,
    normalize: Literal["none", "l2"] = "none",
    precision: Literal["auto", "single", "double"] = "auto",
    threads: int = 0,
    progress: Optional[Callable[[dict[str, Any]], Optional[bool]]] = None,  # {iteration, max_iterations, seconds}
    poll_s: float = 0.05,
    nsr_map: Optional[ArrayLike] = None,
    object_distance: Optional[Length] = None,  # refocus (with mask=)
) -> Result: ...
def decode_batch(
    captures: Iterable[Union[ArrayLike, PathLikeStr]],  # arrays and/or image or RAW paths
    bayer: Optional[Literal["sum2x2", "green", "g", "r", "b"]] = None,  # as read_image
    **kwargs: Any,  # decode()'s keywords: psf= or mask=, method, nsr, iters, ...
) -> list[Result]: ...
def metrics(
    mask: MaskLike,
    snr_db: Optional[Levels] = None,  # dB; None: 30
    scenes: Sequence[str] = ("letter-R", "usaf", "siemens-star"),  # as compare and search
    prior_scenes: int = 16,
    nsr: str = "tuned",
    tv_lambda: str = "1e-3",
    tv_iterations: int = 200,
    seed: int = 1,
    name: str = "mask",
    photons: Optional[Levels] = None,  # electrons per pixel through one pinhole (photon model)
    read_noise: Optional[float] = None,  # rms electrons
    dark_current: Optional[float] = None,  # mean electrons per pixel
    full_well: Optional[float] = None,  # electrons
    bits: Optional[int] = None,  # ADC bits 1..24, needs full_well
    optical_density: Optional[float] = None,  # film OD (transmission 10^-OD)
    prior: Prior = "natural",
    robust: Optional[str] = None,  # as --robust: "size=44um,jitter=2um,missing=0.01"
) -> Result: ...
def score(
    masks: Sequence[MaskLike],
    metrics: Union[str, Sequence[str]] = "sidelobes,spectrum,analytic,wiener",  # or tv, depth
    scenes: Sequence[str] = ("letter-R", "usaf", "natural"),  # as the score command
    snr_db: Optional[Levels] = None,  # dB; None: 20, 30, 40
    photons: Optional[Levels] = None,  # electrons per pixel through one pinhole (photon model)
    read_noise: Optional[float] = None,  # rms electrons
    dark_current: Optional[float] = None,  # mean electrons per pixel
    full_well: Optional[float] = None,  # electrons
    bits: Optional[int] = None,  # ADC bits 1..24, needs full_well
    optical_density: Optional[float] = None,  # film OD (transmission 10^-OD)
    prior: Prior = "natural",
    prior_scenes: int = 16,
    nsr: str = "0.01",
    tv_lambda: str = "1e-3",
    tv_iterations: int = 200,
    noise_seeds: int = 1,  # realisations per scene and level, 1..1000
    seed: int = 0,
    robust: Optional[str] = None,  # "size=5um,jitter=2um,missing=0.01"
    robust_decoder: bool = False,  # adds {psf, nsr_map, floored} arrays (needs robust)
    allow_violations: bool = False,
    depth_from: Optional[float] = None,  # metres; None, None: working distance / 2 .. x 2
    depth_to: Optional[float] = None,  # metres (depth needs photons)
) -> Result: ...
def sidelobes(pattern: Pattern) -> Result: ...
def autocorrelation(pattern: Pattern) -> npt.NDArray[np.int32]: ...
def spectrum_metrics(pattern: Pattern) -> Result: ...
def analytic_error(
    mask: MaskLike,
    snr_db: Optional[float] = None,
    photons: Optional[float] = None,
    read_noise: Optional[float] = None,
    dark_current: Optional[float] = None,
    full_well: Optional[float] = None,
    bits: Optional[int] = None,
    optical_density: Optional[float] = None,
    filter: str = "optimal",
    prior_scenes: int = 16,
    prior_first_seed: int = 1000,
) -> Result: ...
def simulated_quality(
    mask: MaskLike,
    scenes: Sequence[str] = ("letter-R", "usaf"),
    decoder: Literal["wiener", "tv"] = "wiener",
    snr_db: Optional[float] = None,
    photons: Optional[float] = None,
    read_noise: Optional[float] = None,
    dark_current: Optional[float] = None,
    full_well: Optional[float] = None,
    bits: Optional[int] = None,
    optical_density: Optional[float] = None,
    weight: str = "tuned",
    noise_seeds: int = 1,
    seed: int = 0,
    tv_iterations: int = 200,
) -> Result: ...
def search(
    camera: Optional[Camera] = None,
    grid: int = 16,
    holes: Union[int, str] = 20,  # K, or a range "A..B": the best mask per K
    tiles: int = 2,
    spacing: float = 2.0,
    kernel: str = "auto",
    kernel_path: str = "",
    pixels_per_cell: Optional[int] = None,
    strategy: Literal["random", "anneal"] = "anneal",
    time: str = "20s",
    evals: int = 0,
    threads: int = 1,
    seed: int = 1,
    top: int = 5,
    snr_db: Optional[float] = None,  # dB; None: 30 (search takes one level)
    filter: str = "auto",  # auto: tuned with photons, optimal with snr_db
    w_analytic: float = 1.0,
    w_max_sidelobe: float = 0.0,
    w_sidelobe_energy: float = 0.0,
    w_min_spectrum: float = 0.0,
    prior_scenes: int = 16,
    keep_out: Literal["none", "border"] = "none",
    rerank_scenes: Sequence[str] = ("letter-R", "usaf", "siemens-star"),
    rerank_tv: bool = True,
    rank_by: Literal["wiener", "tv"] = "wiener",
    allow_spectral_zeros: bool = False,
    progress: Optional[Callable[[dict[str, Any]], Optional[bool]]] = None,
    photons: Optional[float] = None,  # one level
    read_noise: Optional[float] = None,
    dark_current: Optional[float] = None,
    full_well: Optional[float] = None,
    bits: Optional[int] = None,
    optical_density: Optional[float] = None,
    prior: Prior = "natural",
    robust: Optional[str] = None,  # as --robust: "size=44um,jitter=2um,missing=0.01"
    objective: Literal["nominal", "robust"] = "nominal",  # robust needs robust
    checkpoint: Optional[str] = None,  # chains' state written here (needs evals)
    checkpoint_every: int = 0,  # evaluations per chain between checkpoints
    resume: Optional[str] = None,  # continue from a checkpoint of the same settings
    depth_weight: float = 0.0,  # W of the depth term, dB per dB (needs photons)
    depth_from: Optional[float] = None,  # metres; None, None: working distance / 2 .. x 2
    depth_to: Optional[float] = None,  # metres
) -> Result: ...
def sweep(
    *,
    product: Optional[dict[str, Sequence[Any]]] = None,  # {keyword: [values]} (file's "grid")
    points: Optional[Sequence[dict[str, Any]]] = None,  # or a list of points
    progress: Optional[Callable[[dict[str, Any]], Optional[bool]]] = None,
    **kwargs: Any,  # search()'s keywords: the base of every point (evals required)
) -> Result: ...
def compare(
    masks: Sequence[MaskLike],
    report: Optional[str] = None,
    baselines: bool = False,
    baseline_count: int = 100,
    snr_db: Optional[Levels] = None,  # dB; None: 30
    scenes: Sequence[str] = ("letter-R", "usaf", "siemens-star"),  # search's re-rank scenes
    prior_scenes: int = 16,
    nsr: str = "tuned",
    tv_lambda: str = "1e-3",
    tv_iterations: int = 200,
    seed: int = 1,
    allow_violations: bool = False,
    photons: Optional[Levels] = None,  # electrons per pixel through one pinhole (photon model)
    read_noise: Optional[float] = None,  # rms electrons
    dark_current: Optional[float] = None,  # mean electrons per pixel
    full_well: Optional[float] = None,  # electrons
    bits: Optional[int] = None,  # ADC bits 1..24, needs full_well
    optical_density: Optional[float] = None,  # film OD (transmission 10^-OD)
    prior: Prior = "natural",
    robust: Optional[str] = None,  # as --robust: "size=44um,jitter=2um,missing=0.01"
    depth: bool = False,  # the depth keys of score(metrics="depth") (needs photons)
    depth_from: Optional[float] = None,  # metres; None, None: working distance / 2 .. x 2
    depth_to: Optional[float] = None,  # metres
) -> Result: ...

class Layout:
    @property
    def polygons(self) -> list[npt.NDArray[np.int64]]: ...  # (k, 2) x, y in nm
    @property
    def annotations(self) -> list[npt.NDArray[np.int64]]: ...
    @property
    def active_area(self) -> tuple[int, int, int, int]: ...
    @property
    def extent(self) -> tuple[int, int, int, int]: ...
    @property
    def tone(self) -> str: ...
    mirrored: bool
    grid_nm: int
    mask_hash: str

def layout(
    mask: MaskLike,
    tone: str = "clear",
    shape: str = "square",
    sides: Optional[int] = None,  # shape polygon only (default 8)
    mirror: bool = False,
    marks: bool = False,
    label: Optional[str] = None,
    frame: Length = "0",
    chord_tol: Length = "auto",
    grid: Length = "1nm",
    hole_side: Optional[Length] = None,
    max_vertices: int = 199,
    allow_spacing_violations: bool = False,
) -> Layout: ...
def fabrication_bytes(
    layout: Layout,
    format: Literal["svg", "pdf", "gds", "dxf", "gerber", "png"],
    layer: int = 1,
    datatype: int = 0,
    dxf_layer: str = "PINMASK",
    dpi: float = 2400.0,
    margin: Length = "10mm",
) -> bytes: ...
def export_mask(
    mask: MaskLike,
    out_dir: str,
    formats: Optional[Sequence[str]] = None,  # None: the vendor preset's, as the command
    stem: Optional[str] = None,
    tone: Optional[str] = None,  # None: the vendor preset's, else clear
    shape: str = "square",
    sides: Optional[int] = None,  # shape polygon only (default 8)
    mirror: bool = False,
    marks: bool = False,
    label: bool = False,
    label_id: str = "",
    frame: Optional[Length] = None,  # None: the vendor preset's, else 0
    chord_tol: Length = "auto",
    grid: Optional[Length] = None,  # None: the vendor preset's, else 1nm
    hole_side: Optional[Length] = None,
    max_vertices: Optional[int] = None,  # None: the vendor preset's, else 199
    layer: int = 1,
    datatype: int = 0,
    dxf_layer: str = "PINMASK",
    dpi: Optional[float] = None,
    margin: Length = "10mm",
    vendor: str = "none",
    require_drc_clean: bool = False,
    allow_spacing_violations: bool = False,
    min_feature: Optional[str] = None,
    min_space: Optional[str] = None,
    units: Optional[Literal["um", "mm", "in"]] = None,  # DXF unit, GDSII/OASIS user unit
    emulsion: Optional[Literal["up", "down"]] = None,
    draw: Optional[Literal["film", "polygons"]] = None,  # PDF/PNG/SVG
    circles: Optional[Literal["native", "polygon"]] = None,  # DXF/Gerber round pinholes
    hierarchy: Literal["flat", "cells", "auto"] = "auto",  # GDSII
    kerf: Optional[Length] = None,  # laser kerf: holes drawn this much smaller
    max_snap_error: Optional[Length] = None,  # tiff1
    psf: bool = True,  # also <stem>.psf.tiff + sidecar, as the command (unless --no-psf)
    npy: bool = False,  # also <stem>.psf.npy
    write_on_violations: bool = False,  # write the files of a failed design-rule check
) -> Result: ...
def check(
    input: Union[Mask, PathLikeStr],
    mask: Optional[MaskLike] = None,
    vendor: Optional[str] = None,  # None: the export sidecar's rules, else film
    min_gap: Optional[Length] = None,
    min_space: Optional[Length] = None,  # alias of min_gap
    min_feature: Optional[Length] = None,
    min_spacing: Optional[Length] = None,
    max_vertices: Optional[int] = None,
    list: int = 20,
    max_xor_um2: float = 0.0,
    shape: Optional[str] = None,  # square | circle | polygon (None: sidecar, else square)
    sides: Optional[int] = None,
    hole_side: Optional[Length] = None,
    frame: Optional[Length] = None,
    chord_tol: Optional[Length] = None,
    tone: Optional[str] = None,
    units: Optional[str] = None,
    mirror: bool = False,
    no_sidecar: bool = False,  # ignore NAME.export.json beside a fabrication file
) -> Result: ...
def calibrate(
    point: ArrayLike,
    mask: MaskLike,
    dark: Optional[ArrayLike] = None,
    max_rotation_deg: float = 5.0,  # counter-clockwise on screen (rows down) positive
    pitch_range: float = 0.05,
    threshold_sigmas: float = 6.0,
    saturation_level: Optional[float] = None,
    pixel_binning: int = 1,
) -> Result: ...  # the keys of `pinmask calibrate --json`; psf, kernel... as arrays
def depth(
    mask: MaskLike,
    distances: Optional[Sequence[float]] = None,  # object distances, m (inf allowed)
    from_m: Optional[float] = None,  # a range from_m..to_m (inf allowed), steps points in 1/u
    to_m: Optional[float] = None,
    steps: Optional[int] = None,  # points of the range (None: 8); not with distances
    snr_db: Optional[float] = None,  # one level, dB; None: 30; inf: noiseless
    photons: Optional[float] = None,  # electrons per pixel through one pinhole (photon model)
    read_noise: Optional[float] = None,  # rms electrons
    dark_current: Optional[float] = None,  # mean electrons per pixel
    full_well: Optional[float] = None,  # electrons
    bits: Optional[int] = None,  # ADC bits 1..24, needs full_well
    optical_density: Optional[float] = None,  # film OD (transmission 10^-OD)
    nsr: str = "tuned",  # Wiener NSR: 'tuned' or a number > 0
    scenes: Sequence[str] = ("letter-R", "natural"),
    tv: bool = True,
    seed: int = 1,
) -> list[Result]: ...  # one dict per distance, the keys of `pinmask depth --json`
def depthmap(
    capture: Union[PathLikeStr, ArrayLike],  # grey (colour: channels averaged) or an image path
    mask: Optional[MaskLike] = None,  # the PSFs from its exact geometry (or psf_stack)
    from_m: Optional[Union[float, str]] = None,  # nearest plane, m or "40cm" (None: design's)
    to_m: Optional[Union[float, str]] = None,  # farthest plane, m or "2m" (inf; None: design's)
    steps: Optional[int] = None,  # planes, equally spaced in 1/u (None: one resolvable step)
    nsr: float = 0.01,  # Wiener NSR of every decode
    window: int = 121,  # odd box side of the cost, px
    smooth: float = 8.0,  # smoothness weight of the labels (0: lowest-cost plane per pixel)
    psf_stack: Optional[Sequence[tuple[Union[float, str], ArrayLike]]] = None,  # (distance, PSF)
    background: Union[None, float, Literal["none", "corner"]] = "none",  # counts off the capture
    downsample: int = 0,  # rounds of 2x2 box averaging of capture and PSFs
    output_dir: Optional[str] = None,  # write the command's files there (None: nothing written)
) -> Result: ...  # `pinmask depthmap --json`'s dict; depth_m, confidence... arrays
def depth_fisher(
    mask: MaskLike,
    object_distance_m: float,  # u, m (finite)
    photons: float = 20000.0,  # electrons of the point source over one period
    read_noise: float = 0.0,  # rms electrons
    rows: int = 0,  # window; 0: the sensor
    cols: int = 0,
) -> Result: ...  # fisher_inverse_m2, crb_inverse_per_m, crb_distance_m, ...
def is_library_buffer(array: object) -> bool: ...
def input_copies() -> int: ...
