// The coded-pinhole-lens camera (docs/design.md section 2). Symbols and units, once for design/:
//   u  object_distance_m   object to mask/lens distance (may be +inf: distant object)
//   f' lens_focal_m        focal length of the thin lens the film sits on (+inf: no lens)
//   f  sensor_distance_m   lens to sensor distance (f < f' is the designed case; f = f' is the
//                          Fraunhofer limit; f > f' is past focus; all are legal)
//   d  pinhole_m           side of one square pinhole = side of one pattern cell
//   w  pixel_pitch_m       sensor pixel pitch
//   lambda wavelength_m    design wavelength (the centre of the band)
//   B  bandwidth_m         full width at half maximum of the light's spectrum (0: one wavelength;
//                          design/optics/spectrum samples it for the kernels)
// All lengths in metres.
#pragma once

namespace pinmask {

struct Camera {
    double object_distance_m = 6.0;
    double lens_focal_m = 0.120;
    double sensor_distance_m = 0.055;
    double wavelength_m = 550e-9;
    double bandwidth_m = 0.0;
    double pixel_pitch_m = 30e-6;
    double pinhole_m = 440e-6;
    int sensor_cols = 720;
    int sensor_rows = 480;
};

// The paper's prototype: u = 6 m, f' = 120 mm, f = 55 mm, d = 440 um, w = 30 um, 720 x 480,
// lambda = 550 nm.
Camera paper_camera();

// Throws InvalidInput naming the first field that is not physical (non-finite where finiteness
// is required, zero or negative lengths, sensor size < 1). u and f' may be +inf. The bandwidth
// may be 0 and at most half the wavelength (design/optics/spectrum: its samples stay at positive
// wavelengths).
void validate(const Camera& camera);

}  // namespace pinmask
