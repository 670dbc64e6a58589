#include "tools/bench/lao_options.h"

#include "base/error.h"

namespace curette::bench {

OptionSpec unseenVoxelsOption() {
    return {"unseen-voxels", true, "skip (default) or compute: LAO rays also from voxels no visible sample reads (same image)"};
}

void applyUnseenVoxelsOption(const CommandLine& cl, LaoSettings& lao) {
    std::string choice = cl.valueOr("unseen-voxels", "skip");
    if (choice != "skip" && choice != "compute") throw InputError("<command line>", "--unseen-voxels", "skip or compute", "\"" + choice + "\"");
    lao.onlyWhereSeen = choice == "skip";
}

OptionSpec recastOption() {
    return {"recast", true, "changed (default) or all: pixels an exact frame after mesh motions casts again (same image)"};
}

bool recastOnlyChanged(const CommandLine& cl) {
    std::string choice = cl.valueOr("recast", "changed");
    if (choice != "changed" && choice != "all") throw InputError("<command line>", "--recast", "changed or all", "\"" + choice + "\"");
    return choice == "changed";
}

}  // namespace curette::bench
