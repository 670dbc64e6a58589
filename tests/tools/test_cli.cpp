// The `curette` executable: exit codes, one clear error line, PNGs written atomically (nothing left behind on
// failure), `info` on the real head.
#include "tests/tools/run_curette.h"
#include "tools/commands/commands.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <sys/wait.h>

namespace {

using curette::testing::Invocation;
Invocation run(const std::string& arguments) { return curette::testing::runCurette(arguments); }

const std::string kSource = CURETTE_SOURCE_DIR;

std::filesystem::path scratch() {
    auto dir = std::filesystem::temp_directory_path() / ("curette-cli-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return dir;
}

TEST(Cli, UsageAndUnknownCommands) {
    EXPECT_EQ(run("--help").exitCode, 0);
    Invocation unknown = run("paint");
    EXPECT_EQ(unknown.exitCode, 2);
    EXPECT_NE(unknown.output.find("unknown command"), std::string::npos);
}

// Every command's help from the same table its parser reads: it exits 0 and names every option, and every
// option has a line of help (so an option added without help fails here).
TEST(Cli, EveryCommandHasHelpNamingEveryOption) {
    using curette::commands::commandTable;
    ASSERT_GE(commandTable().size(), 17u);
    for (const curette::commands::Command& c : commandTable()) {
        for (const char* flag : {" --help", " -h"}) {
            Invocation r = run(c.spec.name + flag);
            EXPECT_EQ(r.exitCode, 0) << c.spec.name << flag << "\n" << r.output;
            EXPECT_EQ(r.output.rfind("usage: curette " + c.spec.name, 0), 0u) << r.output;
            for (const curette::OptionSpec& o : c.spec.options) {
                EXPECT_FALSE(o.help.empty()) << c.spec.name << " --" << o.name << " has no help";
                EXPECT_NE(r.output.find("  --" + o.name + (o.takesValue ? " " : "  ")), std::string::npos)
                    << c.spec.name << " --help does not name --" << o.name << ":\n" << r.output;
            }
        }
    }
    // A group's help lists its sub-commands.
    for (const char* group : {"bench", "tracts"}) {
        Invocation r = run(std::string(group) + " --help");
        EXPECT_EQ(r.exitCode, 0) << r.output;
        for (const curette::commands::Command& c : commandTable())
            if (c.spec.name.rfind(std::string(group) + " ", 0) == 0) {
                EXPECT_NE(r.output.find("  " + c.spec.name), std::string::npos) << r.output;
            }
    }
}

// The top-level usage names every command and, in that command's lines, every option (--gpu in a footnote that
// names the commands that take it).
TEST(Cli, TheUsageNamesEveryCommandAndItsOptions) {
    Invocation r = run("--help");
    ASSERT_EQ(r.exitCode, 0);
    for (const curette::commands::Command& c : curette::commands::commandTable()) {
        std::size_t start = r.output.find("\n  " + c.spec.name + (c.spec.synopsis.empty() ? "\n" : " " + c.spec.synopsis + "\n"));
        ASSERT_NE(start, std::string::npos) << c.spec.name << " is not in the usage:\n" << r.output;
        std::size_t end = start + 1;
        while ((end = r.output.find('\n', end + 1)) != std::string::npos && r.output.compare(end + 1, 4, "    ") == 0) {}
        std::string block = r.output.substr(start, end - start);
        std::size_t footnote = r.output.find("--gpu N|llvmpipe|surfaceless chooses");
        ASSERT_NE(footnote, std::string::npos) << r.output;
        for (const curette::OptionSpec& o : c.spec.options) {
            if (o.name == "gpu") EXPECT_NE(r.output.find(c.spec.name, footnote), std::string::npos) << c.spec.name << " not in the --gpu note";
            else EXPECT_NE(block.find("--" + o.name), std::string::npos) << "--" << o.name << " missing from:\n" << block;
        }
    }
    Invocation noArguments = run("");
    EXPECT_EQ(noArguments.exitCode, 2);
    EXPECT_EQ(noArguments.output, r.output) << "without a command: the same usage, as an error";
}

TEST(Cli, VersionIsTheProjectVersion) {
    std::string text = curette::testing::readTextFile(kSource + "/CMakeLists.txt");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(text, m, std::regex(R"(project\(curette VERSION ([0-9.]+))")));
    Invocation r = run("--version");
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_EQ(r.output.rfind("curette " + m[1].str(), 0), 0u) << r.output;
}

// Unknown options and sub-commands exit 2 and say which; so does a group without its sub-command.
TEST(Cli, UnknownOptionsExit2NamingThem) {
    for (const curette::commands::Command& c : curette::commands::commandTable()) {
        Invocation r = run(c.spec.name + " --no-such-option");
        EXPECT_EQ(r.exitCode, 2) << c.spec.name << "\n" << r.output;
        EXPECT_NE(r.output.find("--no-such-option"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("error"), std::string::npos) << r.output;
    }
    for (const char* arguments : {"bench paint", "tracts paint"}) {
        Invocation r = run(arguments);
        EXPECT_EQ(r.exitCode, 2) << r.output;
        EXPECT_NE(r.output.find("\"paint\""), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("--help"), std::string::npos) << "says where the sub-commands are listed: " << r.output;
    }
    EXPECT_EQ(run("bench").exitCode, 2);
    Invocation value = run("render --size");
    EXPECT_EQ(value.exitCode, 2);
    EXPECT_NE(value.output.find("--size"), std::string::npos) << value.output;
}

TEST(Cli, InfoDescribesTheHead) {
    Invocation r = run("info /usr/share/mricron/templates/ch2.nii.gz");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("181 x 217 x 181"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("-125.0000"), std::string::npos);
    EXPECT_NE(r.output.find("max 254"), std::string::npos);
    EXPECT_NE(r.output.find("histogram"), std::string::npos);
}

TEST(Cli, RenderWritesAPngAndBadInputLeavesNothing) {
    auto out = scratch() / "head.png";
    std::filesystem::remove(out);
    Invocation ok = run("render --scene " + kSource + "/assets/scenes/head.json --out " + out.string() + " --size 64x48 --shading solid");
    ASSERT_EQ(ok.exitCode, 0) << ok.output;
    std::ifstream png(out, std::ios::binary);
    char magic[8] = {};
    png.read(magic, 8);
    EXPECT_EQ(std::string(magic + 1, 3), "PNG");

    auto bad = scratch() / "bad.png";
    std::filesystem::remove(bad);
    struct Case {
        std::string arguments, expected;
        int code;
    };
    for (const Case& c : {Case{"--scene " + kSource + "/assets/scenes/head.json --out " + bad.string() + " --size 0x10", "--size", 2},
                          Case{"--scene " + kSource + "/assets/scenes/head.json --out " + bad.string() + " --shading toon", "--shading", 2},
                          Case{"--scene /nonexistent.json --out " + bad.string(), "/nonexistent.json", 2},
                          Case{"--scene " + kSource + "/assets/scenes/head.json --out " + bad.string() + " --colour red", "--colour", 2},
                          Case{"--scene " + kSource + "/assets/scenes/head.json", "--out", 2},
                          Case{"--scene " + kSource + "/assets/scenes/head.json --out /nonexistent-dir/x.png --size 8x8", "/nonexistent-dir/x.png", 3}}) {
        Invocation r = run("render " + c.arguments);
        EXPECT_EQ(r.exitCode, c.code) << c.arguments << "\n" << r.output;
        EXPECT_NE(r.output.find(c.expected), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("error"), std::string::npos) << r.output;
        EXPECT_FALSE(std::filesystem::exists(bad)) << "no partial output";
    }
    // Nothing but the PNG in the output directory: no temporary files left behind.
    for (const auto& entry : std::filesystem::directory_iterator(scratch()))
        EXPECT_EQ(entry.path().extension(), ".png") << entry.path();
}

TEST(Cli, ASceneWhoseVolumeIsMissingNamesTheKey) {
    auto scene = scratch() / "missing-volume.json";
    std::ofstream(scene) << R"({"volume": {"path": "nowhere.nii.gz"}, "transfer_function": ")" << kSource << R"(/assets/tf/mri_t1.json"})";
    Invocation r = run("render --scene " + scene.string() + " --out " + (scratch() / "m.png").string());
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.output.find("volume.path"), std::string::npos) << r.output;
}

}  // namespace
