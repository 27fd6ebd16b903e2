#include "design/optics/design_run.hpp"

#include "core/errors/error.hpp"
#include "core/errors/field_names.hpp"
#include "design/optics/default_pinhole.hpp"
#include "design/optics/fab_grid.hpp"
#include "design/psf/kernel.hpp"

namespace pinmask {

GridSnap DesignRequest::grid() const {
    const auto say = [&](const std::string& w) { return spell ? spell(w) : w; };
    GridSnap g{false, kDefaultFabGridNm, "default"};
    if (fab_grid_m && vendor)
        throw invalid_field(field_ref("fab_grid"), fab_grid_text,
                            "and " + field_ref("vendor") + " both set the grid: give one of them");
    if (fab_grid_m) {
        g.grid_nm = fab_grid_nm(*fab_grid_m, field_ref("fab_grid"));
        g.grid_source = say(field_ref("fab_grid"));
    } else if (vendor) {
        if (!vendor_grid_m)
            throw invalid_field(field_ref("vendor"), *vendor,
                                "is a rule preset without a grid; give an export preset "
                                "(`pinmask export --vendor list`) or " +
                                    field_ref("fab_grid"));
        g.grid_nm = fab_grid_nm(*vendor_grid_m, field_ref("vendor"));
        g.grid_source = "vendor " + *vendor;
    }
    if ((fab_grid_m || vendor) && !pixels_per_cell && !solve)
        throw invalid_field(field_ref(fab_grid_m ? "fab_grid" : "vendor"),
                            fab_grid_m ? fab_grid_text : *vendor,
                            "sets the grid a solved pinhole lands on: use it with " +
                                field_ref("solve") + " pinhole or " + field_ref("pixels_per_cell"));
    return g;
}

DesignReport run_design_request(const DesignRequest& q) {
    const auto spell = [&](const std::string& s) { return q.spell ? q.spell(s) : s; };
    DesignReport r;
    Camera& camera = r.camera;
    camera = q.camera;
    r.snap = q.grid();
    WorkingDistanceOptions wo{q.lsi_tolerance_px, q.pixels_per_cell.value_or(0)};
    if (q.pixels_per_cell || q.solve) {
        // Solving for the nearest N keeps the whole pitch of the pinhole it starts from: a start
        // far from the optimum gives a solution as far from it, so the optimum is said.
        if (!q.pixels_per_cell) r.far_from_optimum = spell(far_from_optimum_note(camera));
        const WorkingDistance start = compute_working_distance(camera, q.geometry, wo);
        if (start.pixels_per_cell > kMaxPixelsPerCell) {
            throw invalid_field(field_ref("solve"), "pinhole",
                                "the pitch at u is " + std::to_string(start.pixels_per_cell) +
                                    " px per cell, above the " + std::to_string(kMaxPixelsPerCell) +
                                    " px limit");
        }
        // d for exactly N at u, then on the fabrication grid (what export draws).
        GridSnap& snap = r.snap;
        snap.exact_m = pinhole_for_pixels_per_cell(camera, start.pixels_per_cell);
        if (const std::string big = solved_pinhole_too_large(snap.exact_m, start.pixels_per_cell);
            !big.empty())
            throw invalid_field(field_ref(q.pixels_per_cell ? "pixels_per_cell" : "solve"),
                                q.pixels_per_cell ? std::to_string(*q.pixels_per_cell) : "pinhole",
                                big);
        snap.on_grid_m = pinhole_on_grid_m(snap.exact_m, snap.grid_nm);
        snap.solved = true;
        camera.pinhole_m = snap.on_grid_m;
        snap.pitch_shift_px = pixels_per_cell_at(camera, camera.object_distance_m) -
                              static_cast<double>(start.pixels_per_cell);
        wo.pixels_per_cell = static_cast<int>(start.pixels_per_cell);
    }
    r.optics = compute_optics(camera, q.geometry, q.model, {q.lsi_tolerance_px});
    r.working = compute_working_distance(camera, q.geometry, wo);
    // The kernel psf would build for this design (its band, the model over the band, the energy
    // its support keeps), so design warns where psf would.
    r.kernel = design_kernel(camera, q.geometry.n, r.working.pixels_per_cell, q.kernel);
    if (r.kernel.kernel) {
        r.optics.kernel_model = r.kernel.kernel->model;
        r.optics.kernel_reason = r.kernel.kernel->model_reason;
    }
    KernelValidity& validity = r.kernel.validity;
    for (auto& w : validity.warnings) w = spell(w);
    if (!validity.model_accurate)
        r.optics.kernel_reason = "NOT accurate: " + validity.warnings.front();
    // The spacing rule against the pinhole count: the proven packing bound, so a design that no
    // search or generator can realise says so before any of them runs.
    r.packing = packing_upper_bound(q.geometry.n, q.spacing_cells);
    r.spacing_cells = q.spacing_cells;
    r.input_sources = q.input_sources;
    if (r.snap.solved && !r.input_sources.empty())
        r.input_sources.front().second = "solved for N px per cell at u, on the " +
                                         std::to_string(r.snap.grid_nm) + " nm fabrication grid";
    return r;
}

}  // namespace pinmask
