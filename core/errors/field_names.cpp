#include "core/errors/field_names.hpp"

namespace pinmask {

std::string field_ref(std::string_view name) {
    std::string out;
    out.reserve(name.size() + 2);
    out += '`';
    out += name;
    out += '`';
    return out;
}

bool is_field_name(std::string_view text) {
    if (text.empty()) return false;
    const auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
    if (!letter(text.front())) return false;
    for (const char c : text) {
        if (!letter(c) && !(c >= '0' && c <= '9') && c != '_' && c != '.') return false;
    }
    return true;
}

std::string spell_fields(std::string_view message, FieldSpelling spell) {
    std::string out;
    out.reserve(message.size());
    std::size_t i = 0;
    while (i < message.size()) {
        const std::size_t open = message.find('`', i);
        if (open == std::string_view::npos) break;
        const std::size_t close = message.find('`', open + 1);
        if (close == std::string_view::npos) break;
        const std::string_view name = message.substr(open + 1, close - open - 1);
        out.append(message.substr(i, open - i));
        if (is_field_name(name)) {
            const std::optional<std::string> spelled = spell ? spell(name) : std::nullopt;
            out += spelled ? *spelled : std::string(name);
            i = close + 1;
        } else {
            out += '`';  // not a reference: keep the backquote, look again after it
            i = open + 1;
        }
    }
    out.append(message.substr(i));
    return out;
}

}  // namespace pinmask
