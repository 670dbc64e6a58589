// The `curette` executable: exit codes, one clear error line, PNGs written atomically (nothing left behind on
// failure), `info` on the real head.
#include "tests/tools/run_curette.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
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
