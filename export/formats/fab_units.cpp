#include "export/formats/fab_units.hpp"

#include "core/errors/error.hpp"

namespace pinmask {

FabUnit parse_fab_unit(std::string_view text, std::string_view field) {
    if (text == "um") return FabUnit::kMicrometre;
    if (text == "mm") return FabUnit::kMillimetre;
    if (text == "in") return FabUnit::kInch;
    throw invalid_field(std::string(field), std::string(text), "must be one of um, mm, in");
}

std::string fab_unit_name(FabUnit unit) {
    switch (unit) {
        case FabUnit::kMicrometre:
            return "um";
        case FabUnit::kMillimetre:
            return "mm";
        case FabUnit::kInch:
            return "in";
    }
    return "?";
}

std::string fab_unit_words(FabUnit unit) {
    switch (unit) {
        case FabUnit::kMicrometre:
            return "micrometres";
        case FabUnit::kMillimetre:
            return "millimetres";
        case FabUnit::kInch:
            return "inches";
    }
    return "?";
}

std::int64_t nm_per_unit(FabUnit unit) {
    switch (unit) {
        case FabUnit::kMicrometre:
            return 1000;
        case FabUnit::kMillimetre:
            return 1000000;
        case FabUnit::kInch:
            return 25400000;
    }
    return 1;
}

int dxf_insunits(FabUnit unit) {
    switch (unit) {
        case FabUnit::kMicrometre:
            return 13;
        case FabUnit::kMillimetre:
            return 4;
        case FabUnit::kInch:
            return 1;
    }
    return 0;
}

}  // namespace pinmask
