// The export transaction (io/export_files): the folder holds exactly the files export_outputs
// names, each fabrication file the bytes the pipeline made, the sidecar the text returned; a
// design-rule failure leaves the folder as it was.
#include <doctest/doctest.h>

#include <filesystem>
#include <set>

#include "core/errors/error.hpp"
#include "io/export_files.hpp"
#include "tests/export/export_fixtures.hpp"
#include "tests/support/cli_run.hpp"

using namespace pinmask;
namespace fs = std::filesystem;

namespace {

std::set<fs::path> listing(const fs::path& dir) {
    std::set<fs::path> out;
    for (const auto& e : fs::directory_iterator(dir)) out.insert(e.path());
    return out;
}

}  // namespace

TEST_CASE("write_export: the files export_outputs names, as the pipeline made them") {
    const Mask mask = pinmask::test::golden_mask();
    for (bool no_psf : {true, false}) {
        INFO("no_psf " << no_psf);
        const pinmask::test::TempDir dir("export-files");
        ExportRequest f;
        f.formats = "gds,svg,png";
        f.no_psf = no_psf;
        f.input = "golden.mask.json";
        const ExportOptions o = export_options_from(f, mask, "g");
        std::set<fs::path> named;
        for (const io::ExportOutput& x : io::export_outputs(f, o, dir.path, "g"))
            named.insert(x.path);
        const io::ExportWritten w = io::write_export(mask, f, o, dir.path, "g");
        CHECK(listing(dir.path) == named);
        CHECK(named.size() == (no_psf ? 4u : 6u));  // 3 files + sidecar (+ PSF and its sidecar)
        CHECK(w.psf.size() == (no_psf ? 0u : 2u));
        REQUIRE(w.summary.files.size() == 3);
        REQUIRE(w.sidecar.files.size() == 3);
        for (std::size_t i = 0; i < 3; ++i) {
            const ExportedFile& e = w.summary.files[i];
            CHECK(pinmask::test::slurp(dir.path / ("g" + e.extension)) == e.bytes);
            CHECK(w.sidecar.files[i].verification.starts_with("read back"));
        }
        CHECK(pinmask::test::slurp(dir.path / "g.export.json") == w.sidecar_text);
    }
}

TEST_CASE("write_export: a design-rule failure writes nothing") {
    const Mask mask = pinmask::test::golden_mask();
    const pinmask::test::TempDir dir("export-files-fail");
    ExportRequest f;
    f.formats = "gds";
    f.min_feature = "1mm";  // wider than every 440 um pinhole
    const ExportOptions o = export_options_from(f, mask, "g");
    CHECK_THROWS_AS(io::write_export(mask, f, o, dir.path, "g"), RuntimeFailure);
    CHECK(listing(dir.path).empty());
}
