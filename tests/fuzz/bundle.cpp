#include "fuzz/bundle.h"

#include <algorithm>
#include <cctype>

namespace snell::fuzz {

namespace {

constexpr std::string_view kHeader = "@@file ";
constexpr std::string_view kSeparator = "\n@@file ";

}  // namespace

bool safe_bundle_name(std::string_view name) {
    if (name.empty() || name.size() > 64) return false;
    int components = 0;
    size_t start = 0;
    while (start <= name.size()) {
        const size_t end = std::min(name.find('/', start), name.size());
        const std::string_view part = name.substr(start, end - start);
        if (part.empty() || part == "." || part == ".." || ++components > 3) return false;
        for (char c : part)
            if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-')) return false;
        start = end + 1;
    }
    return true;
}

std::vector<BundleFile> parse_bundle(std::string_view input) {
    std::vector<BundleFile> files;
    if (!input.starts_with(kHeader)) {
        files.push_back({"scene.xml", std::string(input)});
        return files;
    }
    size_t pos = 0;  // at a header
    while (pos < input.size()) {
        const size_t name_begin = pos + kHeader.size();
        const size_t name_end = std::min(input.find('\n', name_begin), input.size());
        const size_t data_begin = std::min(name_end + 1, input.size());
        size_t next = input.find(kSeparator, name_end);
        const size_t data_end = next == std::string_view::npos ? input.size() : next;
        std::string name(input.substr(name_begin, name_end - name_begin));
        const bool first = files.empty();
        if (first && !safe_bundle_name(name)) name = "scene.xml";
        const bool duplicate =
            std::any_of(files.begin(), files.end(), [&](const BundleFile& f) { return f.name == name; });
        if (files.size() < kMaxBundleFiles && safe_bundle_name(name) && !duplicate)
            files.push_back({std::move(name), std::string(input.substr(data_begin, data_end - data_begin))});
        if (next == std::string_view::npos) break;
        pos = next + 1;
    }
    return files;
}

std::string write_bundle(const std::vector<BundleFile>& files) {
    std::string out;
    for (size_t i = 0; i < files.size(); ++i) {
        if (i) out += '\n';
        out += kHeader;
        out += files[i].name;
        out += '\n';
        out += files[i].data;
    }
    return out;
}

}  // namespace snell::fuzz
