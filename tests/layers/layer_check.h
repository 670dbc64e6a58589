#pragma once
// The include-layer check (docs/architecture.md, "Layers"): which folder may include which, which folders are
// GL-free, and a scan of the source tree against that table.

#include <string>
#include <vector>

namespace curette::layers {

struct Violation {
    std::string file;   // relative to the source root
    int line = 0;
    std::string message;
};

struct Layer {
    std::string folder;                 // "render/model": a top-level folder or one subfolder with its own rule
    std::vector<std::string> includes;  // the layers it may include besides itself
    bool glFree = false;                // no GL header, no gl/ include, no GL call
    bool glCalls = false;               // may call GL itself (gl/, render/ and xr/ only)
};

// Lowest first: the order of the top-level CMakeLists.txt and of the table in docs/architecture.md.
const std::vector<Layer>& layerTable();
// The layer a path belongs to: the longest folder of the table that is a prefix of it ("" when none).
std::string layerOf(const std::string& path);

// The problems in one file, `path` relative to the source root.
std::vector<Violation> checkFile(const std::string& path, const std::string& text);
// Every .h/.cpp below the project's layer folders.
std::vector<Violation> checkTree(const std::string& root);
int filesChecked(const std::string& root);
// The folders below the root that hold C++ sources but belong to no layer (tests/ and the build excluded).
std::vector<std::string> foldersOutsideTheTable(const std::string& root);

}  // namespace curette::layers
