#pragma once
// The sub-commands of the `curette` executable. Each takes the arguments after its name, returns the
// process exit code, and throws InputError/SystemError for main() to report.

#include <string>
#include <vector>

namespace curette::commands {

using Arguments = std::vector<std::string>;

int info(const Arguments& args);     // curette info FILE
int render(const Arguments& args);   // curette render --scene S --out F.png
int view(const Arguments& args);     // curette view --scene S
int bench(const Arguments& args);    // curette bench raycast|cao|dos|input --scene S
int record(const Arguments& args);   // curette record --scene S --out F.jsonl --synthetic FAMILIES
int replay(const Arguments& args);   // curette replay F.jsonl [--check] [--from-reports] [--report]
int report(const Arguments& args);   // curette report --scene S [--session F --frame N] --out DIR
int tracts(const Arguments& args);   // curette tracts synth --from DIR --count N --seed S --out F.tck

}  // namespace curette::commands
