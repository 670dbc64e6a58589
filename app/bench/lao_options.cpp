#include "app/bench/lao_options.h"

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

}  // namespace curette::bench
