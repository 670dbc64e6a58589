// curette tracts synth --from <files or folders> --count N --seed S --jitter MM --out F.tck|F.trk|F.trx: a
// whole-brain-scale tractogram (issue 12) from a few bundles by jittered copies (tools/tract_synthesis.h), written
// (atomically) as MRtrix .tck, TrackVis .trk or TRX by the extension of --out. scripts/setup makes /usr/local/share/curette/tracts-100k.tck with it from dipy's bundles.
#include "tools/command_line.h"
#include "tools/commands/commands.h"
#include "io/tck_writer.h"
#include "io/trk_writer.h"
#include "io/trx_writer.h"
#include "io/tract_file.h"
#include "tools/tract_synthesis.h"
#include "base/error.h"

#include <cstdio>
#include <sstream>

namespace curette::commands {

namespace {

int synth(const CommandLine& cl) {
    if (!cl.positional().empty()) throw InputError("<command line>", cl.positional()[0], "no positional arguments for tracts synth");
    std::filesystem::path out = cl.required("out");
    const std::string format = out.extension().string();
    if (format != ".tck" && format != ".trk" && format != ".trx")
        throw InputError("<command line>", "--out", "a .tck, .trk or .trx file name", "\"" + out.string() + "\"");
    TractSynthesisSettings settings;
    settings.count = static_cast<std::size_t>(CommandLine::parseInt("count", cl.valueOr("count", "100000"), 1, 50'000'000));
    settings.seed = static_cast<std::uint64_t>(CommandLine::parseInt("seed", cl.valueOr("seed", "1"), 0, 2147483647));
    settings.jitterMm = CommandLine::parseDouble("jitter", cl.valueOr("jitter", "3"), 0.0, 100.0);
    std::vector<Tractogram> sources;
    std::stringstream list(cl.required("from"));
    std::size_t sourceStreamlines = 0;
    for (std::string item; std::getline(list, item, ',');) {
        if (item.empty()) continue;
        for (const std::filesystem::path& file : tractFilesUnder(item)) {
            sources.push_back(io::readTractogram(file));
            sourceStreamlines += sources.back().streamlineCount();
        }
    }
    if (sources.empty()) throw InputError("<command line>", "--from", "at least one tract file or folder", "\"" + cl.required("from") + "\"");
    Tractogram result = synthesiseTracts(sources, settings);
    if (format == ".trk") io::writeTrk(out, result);
    else if (format == ".trx") io::writeTrx(out, result);
    else io::writeTck(out, result);
    std::printf("%s: %zu streamlines, %zu points, jittered copies (seed %llu, jitter <= %.3g mm) of %zu streamlines from %zu files\n",
                out.c_str(), result.streamlineCount(), result.points.size(), static_cast<unsigned long long>(settings.seed), settings.jitterMm,
                sourceStreamlines, sources.size());
    return 0;
}

}  // namespace

std::vector<Command> tractsCommands() {
    return {{{"tracts synth", "--from DIR --count N --out F.tck|F.trk|F.trx",
              "a whole-brain-scale tractogram from a few bundles by jittered copies (deterministic: --seed, --jitter)",
              {{"from", true, "tract files or folders of them (comma-separated; folders are searched recursively)"},
               {"count", true, "streamlines to write (default 100000)"},
               {"seed", true, "seed of the jitter (default 1)"},
               {"jitter", true, "bound on each point's displacement, mm (default 3)"},
               {"out", true, "the file to write: .tck (MRtrix), .trk (TrackVis) or .trx (TRX, a stored zip), by extension"}}},
             &synth}};
}

}  // namespace curette::commands
