#include "export/pipeline/film_identity.hpp"

#include "export/formats/gerber_writer.hpp"
#include "export/layout/geometry.hpp"

namespace pinmask {
namespace {

std::string joined(const std::vector<std::string>& names) {
    std::string s;
    for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

FilmIdentityItem layer_item(const FileGeometry& file, FabFormat format,
                            const FilmIdentityExpected& e) {
    FilmIdentityItem it;
    it.what = format == FabFormat::kDxf   ? "DXF layer"
              : format == FabFormat::kGds ? "GDSII layer/datatype"
                                          : "OASIS layer/datatype";
    it.found = file.layers.empty() ? "none" : joined(file.layers);
    it.expected = e.layer.value_or("");
    it.source = e.layer_source;
    if (file.layers.size() > 1) {
        it.ok = false;
        it.message = "geometry on " + std::to_string(file.layers.size()) + " layers (" + it.found +
                     "): a film is one layer, and the shop images only the one it is told" +
                     (e.layer ? " (" + *e.layer + " by " + e.layer_source + ")" : "");
    } else if (e.layer && !file.layers.empty() && file.layers.front() != *e.layer) {
        it.ok = false;
        it.message = "geometry on layer " + it.found + ", not " + *e.layer + " (" + e.layer_source +
                     "): the shop would image an empty layer";
    } else if (file.layers.empty()) {
        it.message = "no geometry whose layer could be compared";
    } else if (e.layer) {
        it.message = it.found + " as " + e.layer_source + " says";
    } else {
        it.message = it.found + ", not compared: " + e.layer_source;
    }
    return it;
}

FilmIdentityItem polarity_item(const FileGeometry& file, const FilmIdentityExpected& e) {
    FilmIdentityItem it;
    it.what = "Gerber polarity";
    const auto p = file.info.find("polarity");
    it.found = p == file.info.end() ? "none" : p->second;
    it.source = e.tone_source;
    // The file's own pinmask comment states its tone: a polarity against it contradicts the file.
    std::optional<Tone> stated;
    if (const auto t = file.info.find("tone"); t != file.info.end())
        stated = parse_tone(t->second, "tone");
    if (e.tone) it.expected = gerber_file_polarity(*e.tone);
    if (e.tone && it.found != it.expected) {
        it.ok = false;
        it.message = p == file.info.end()
                         ? "the file states no polarity (%TF.FilePolarity); " + e.tone_source +
                               " says " + it.expected + " (" + tone_name(*e.tone) + " tone)"
                         : "polarity " + it.found + ", not " + it.expected + " (" +
                               tone_name(*e.tone) + " tone by " + e.tone_source +
                               "): the plotter would expose the inverse film";
    } else if (stated && p != file.info.end() && it.found != gerber_file_polarity(*stated)) {
        it.ok = false;
        it.message = "polarity " + it.found + " contradicts the file's own pinmask comment (tone " +
                     tone_name(*stated) + ": " + gerber_file_polarity(*stated) + ")";
    } else if (e.tone) {
        it.message = it.found + " as " + e.tone_source + " says";
    } else {
        it.message = it.found + ", not compared: " + e.tone_source;
    }
    return it;
}

}  // namespace

bool FilmIdentity::ok() const {
    for (const FilmIdentityItem& i : items)
        if (!i.ok) return false;
    return true;
}

std::vector<const FilmIdentityItem*> FilmIdentity::not_known() const {
    std::vector<const FilmIdentityItem*> out;
    for (const FilmIdentityItem& i : items)
        if (i.expected.empty()) out.push_back(&i);
    return out;
}

FilmIdentity check_film_identity(const FileGeometry& file, FabFormat format,
                                 const FilmIdentityExpected& expected) {
    FilmIdentity id;
    if (format == FabFormat::kGds || format == FabFormat::kOasis || format == FabFormat::kDxf)
        id.items.push_back(layer_item(file, format, expected));
    if (format == FabFormat::kGerber) id.items.push_back(polarity_item(file, expected));
    return id;
}

}  // namespace pinmask
