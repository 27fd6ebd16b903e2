#include "cli/options/command_flags.hpp"

#include <optional>
#include <vector>

#include "cli/options/flag_names.hpp"
#include "core/errors/field_names.hpp"

namespace pinmask::cli {

std::string spell_flags(std::string_view message, const CLI::App& command) {
    // spell_fields takes a plain function: the command is passed through this thread's slot.
    thread_local const CLI::App* current = nullptr;
    current = &command;
    return spell_fields(message, [](std::string_view field) -> std::optional<std::string> {
        std::optional<std::string> flag = flag_spelling(field);
        if (!flag || !current) return flag;
        // "--geometry exact", "--from/--to": the option is the first word.
        const std::string option = flag->substr(0, flag->find_first_of(" /"));
        if (current->get_option_no_throw(option)) return flag;
        std::vector<std::string> having;
        if (const CLI::App* parent = current->get_parent()) {
            for (const CLI::App* sibling :
                 parent->get_subcommands([](const CLI::App*) { return true; }))
                if (sibling->get_option_no_throw(option)) having.push_back(sibling->get_name());
        }
        std::string out = *flag + " (";
        if (having.empty()) {
            out += "not a flag of " + current->get_name();
        } else {
            out += "a flag of pinmask ";
            for (std::size_t i = 0; i < having.size(); ++i) out += (i ? ", " : "") + having[i];
            out += ", not of " + current->get_name();
        }
        return out + ")";
    });
}

}  // namespace pinmask::cli
