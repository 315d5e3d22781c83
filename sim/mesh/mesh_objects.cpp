#include "sim/mesh/mesh_objects.h"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <unordered_set>

#include "sim/core/content_hash.h"
#include "sim/core/input_error.h"
#include "sim/mesh/mesh_io.h"

namespace pelage::sim {

MeshSpec parse_mesh_spec(const std::string &spec) {
    for (size_t hash = spec.find('#'); hash != std::string::npos;
         hash = spec.find('#', hash + 1)) {
        const std::string path = spec.substr(0, hash);
        const size_t slash = path.find_last_of('/');
        const size_t dot = path.find_last_of('.');
        if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
            continue;
        if (!is_mesh_extension(path.substr(dot + 1))) continue;
        const std::string object = spec.substr(hash + 1);
        if (object.empty())
            throw InputError(path, 0, "",
                             "no object name after '#' (write PATH#NAME, or PATH alone "
                             "for every object of the file)");
        return {path, object};
    }
    return {spec, ""};
}

std::vector<std::string> unique_names(const std::vector<std::string> &names) {
    std::vector<std::string> out;
    std::unordered_set<std::string> seen;
    for (const std::string &n : names)
        if (!n.empty() && seen.insert(n).second) out.push_back(n);
    return out;
}

void fail_unknown_object(const std::string &path, const std::string &object,
                         const std::vector<std::string> &names) {
    // A file can hold thousands of named nodes: list the first ones.
    constexpr size_t max_listed = 40;
    std::string list;
    for (size_t i = 0; i < std::min(names.size(), max_listed); ++i)
        list += (i ? ", " : "") + ('"' + names[i] + '"');
    if (names.size() > max_listed)
        list += " and " + std::to_string(names.size() - max_listed) + " more";
    throw InputError(path, 0, "",
                     "no object named \"" + object + "\" (" +
                         (names.empty() ? std::string("the file names no objects")
                                        : "the file's objects: " + list) +
                         ")");
}

std::string mesh_reference_hash(const std::string &spec) {
    ContentHash h;
    if (spec.rfind("procedural:", 0) == 0) {
        h.add(spec);
        return h.hex();
    }
    const MeshSpec m = parse_mesh_spec(spec);
    std::ifstream in(m.path, std::ios::binary);
    if (!in) return "";
    h.add(std::string(std::istreambuf_iterator<char>(in), {}));
    // One object of the file is another mesh than the whole file or another object.
    if (!m.object.empty()) h.add("#" + m.object);
    return h.hex();
}

}  // namespace pelage::sim
