#pragma once
// The include-layer check (docs/architecture.md, "Layers"): which top-level folder may include which, and
// a scan of the source tree against that table.

#include <string>
#include <vector>

namespace curette::layers {

struct Violation {
    std::string file;   // relative to the source root
    int line = 0;
    std::string message;
};

// The problems in one file, `path` relative to the source root (its first component is its folder).
std::vector<Violation> checkFile(const std::string& path, const std::string& text);
// Every .h/.cpp below the project's layer folders.
std::vector<Violation> checkTree(const std::string& root);
int filesChecked(const std::string& root);

}  // namespace curette::layers
