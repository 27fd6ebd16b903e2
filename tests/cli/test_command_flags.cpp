// cli/options/command_flags: a message spelled for one command names only flags that command
// has; a field whose flag it lacks is named with the sibling commands that have it.
#include <doctest/doctest.h>

#include <CLI/CLI.hpp>
#include <string>

#include "cli/options/command_flags.hpp"
#include "core/errors/field_names.hpp"

using pinmask::field_ref;
using pinmask::cli::spell_flags;

TEST_CASE("spell_flags for a command: its own flags as flags, another command's named as such") {
    CLI::App app("pinmask");
    std::string pinhole, energy, kernel_path;
    CLI::App* design = app.add_subcommand("design");
    design->add_option("--pinhole", pinhole);
    CLI::App* psf = app.add_subcommand("psf");
    psf->add_option("--pinhole", pinhole);
    psf->add_option("--energy", energy);
    CLI::App* simulate = app.add_subcommand("simulate");
    simulate->add_option("--energy", energy);
    const std::string message =
        "raise " + field_ref("energy_fraction") + " or give " + field_ref("pinhole_m");
    CHECK(spell_flags(message, *psf) == "raise --energy or give --pinhole");
    CHECK(spell_flags(message, *design) ==
          "raise --energy (a flag of pinmask psf, simulate, not of design) or give --pinhole");
    // A flag no command has: said so, not offered.
    CHECK(spell_flags("give " + field_ref("kernel_path"), *design) ==
          "give --kernel-path (not a flag of design)");
}
