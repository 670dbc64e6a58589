// The command line of stereo, movies and GPU choice, as a user meets it: `render --stereo`, `render
// --turntable` (with a stand-in ffmpeg on PATH that records what it is handed, so no test needs the real one),
// `replay --mp4`, `info --gl` and `--gpu`.
#include "tests/tools/run_curette.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <sys/wait.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace {

using curette::testing::Invocation;
Invocation run(const std::string& arguments) { return curette::testing::runCurette(arguments); }

// `curette arguments` with `environment` ("NAME=value ...") in front of it, through the shell.
Invocation runWith(const std::string& environment, const std::string& arguments) {
    std::string command = environment + " " + std::string(CURETTE_BINARY) + " " + arguments + " 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    std::string output;
    char buffer[4096];
    while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
    int status = pclose(pipe);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

std::filesystem::path scratch(const std::string& name) { return curette::testing::freshScratchFolder("curette-stereo-movie", name); }

std::string readText(const std::filesystem::path& path) { return curette::testing::readTextFile(path); }

// A 24^3 ball with 2 mm voxels, solid shading: cheap to render at any angle.
std::filesystem::path writeBallScene(const std::filesystem::path& dir) {
    std::vector<unsigned char> voxels(24 * 24 * 24);
    for (int k = 0; k < 24; ++k)
        for (int j = 0; j < 24; ++j)
            for (int i = 0; i < 24; ++i) {
                double r = std::sqrt((i - 11.5) * (i - 11.5) + (j - 9.5) * (j - 9.5) + (k - 11.5) * (k - 11.5));
                voxels[static_cast<std::size_t>((k * 24 + j) * 24 + i)] = r < 8 ? static_cast<unsigned char>(120 + 15 * i / 2) : 0;
            }
    std::ofstream(dir / "ball.raw", std::ios::binary).write(reinterpret_cast<const char*>(voxels.data()), static_cast<std::streamsize>(voxels.size()));
    std::ofstream(dir / "scene.json") << R"({
  "volume": {"path": "ball.raw", "format": "raw", "raw": {"dims": [24, 24, 24], "type": "uint8", "spacing": [2, 2, 2]}},
  "transfer_function": {"color": [[0, 0, 0, 0], [120, 0.9, 0.3, 0.2], [255, 0.2, 0.5, 1]], "opacity": [[0, 0], [60, 0], [100, 0.5], [255, 0.9]]},
  "camera": {"target": "center", "distance_mm": 150, "azimuth_deg": 20, "elevation_deg": 10, "fov_deg": 30},
  "shading": "solid",
  "image": {"width": 24, "height": 24}
})";
    return dir / "scene.json";
}

// A stand-in ffmpeg: records its working directory, its arguments (one a line) and the concat list, then
// writes its last argument (the movie) or fails, as `exitCode` says.
std::filesystem::path writeFakeFfmpeg(const std::filesystem::path& dir, int exitCode = 0) {
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "ffmpeg") << "#!/bin/sh\n"
                                  << "pwd -P > \"$FAKE_FFMPEG_LOG\"\n"
                                  << "for a in \"$@\"; do echo \"$a\" >> \"$FAKE_FFMPEG_LOG\"; done\n"
                                  << "cp .frames.ffconcat \"$FAKE_FFMPEG_LOG.list\"\n"
                                  << "for last in \"$@\"; do :; done\n"
                                  << (exitCode ? "echo half > \"$last\"; exit " + std::to_string(exitCode) + "\n" : "echo movie > \"$last\"\n");
    ::chmod((dir / "ffmpeg").c_str(), 0755);
    return dir;
}

std::pair<int, int> pngSize(const std::filesystem::path& png) {
    std::string bytes = readText(png);
    if (bytes.size() < 24) return {0, 0};
    auto be32 = [&](std::size_t at) {
        return (static_cast<unsigned char>(bytes[at]) << 24) | (static_cast<unsigned char>(bytes[at + 1]) << 16) |
               (static_cast<unsigned char>(bytes[at + 2]) << 8) | static_cast<unsigned char>(bytes[at + 3]);
    };
    return {be32(16), be32(20)};
}

TEST(StereoCli, SideBySideIsTwoEyesWideAnaglyphOneAndBadValuesAreRefused) {
    auto dir = scratch("stereo");
    auto scene = writeBallScene(dir).string();
    Invocation sbs = run("render --scene " + scene + " --out " + (dir / "sbs.png").string() + " --size 32x24 --stereo side-by-side");
    ASSERT_EQ(sbs.exitCode, 0) << sbs.output;
    EXPECT_EQ(pngSize(dir / "sbs.png"), std::make_pair(64, 24));
    EXPECT_NE(sbs.output.find("off-axis"), std::string::npos) << sbs.output;
    Invocation red = run("render --scene " + scene + " --out " + (dir / "red.png").string() + " --size 32x24 --stereo anaglyph --eye-separation 40");
    ASSERT_EQ(red.exitCode, 0) << red.output;
    EXPECT_EQ(pngSize(dir / "red.png"), std::make_pair(32, 24));
    struct Case {
        std::string arguments, names;
    };
    for (const Case& c : {Case{"--stereo 3d", "--stereo"}, Case{"--stereo off", "--stereo"}, Case{"--eye-separation 65", "--eye-separation"},
                          Case{"--stereo anaglyph --eye-separation -5", "--eye-separation"}}) {
        Invocation r = run("render --scene " + scene + " --out " + (dir / "bad.png").string() + " " + c.arguments);
        EXPECT_EQ(r.exitCode, 2) << c.arguments << "\n" << r.output;
        EXPECT_NE(r.output.find(c.names), std::string::npos) << r.output;
        EXPECT_FALSE(std::filesystem::exists(dir / "bad.png"));
    }
}

TEST(MovieCli, TheTurntableWritesItsFramesAndHandsExactlyThoseToFfmpeg) {
    auto dir = scratch("turntable");
    auto scene = writeBallScene(dir).string();
    auto fake = writeFakeFfmpeg(dir / "bin");
    auto log = dir / "ffmpeg.log";
    auto frames = dir / "frames";
    std::filesystem::create_directories(frames);
    std::ofstream(frames / "frame_000005.png") << "left by an earlier, longer run";
    std::string env = "PATH=" + fake.string() + ":$PATH FAKE_FFMPEG_LOG=" + log.string();
    Invocation r = runWith(env, "render --scene " + scene + " --turntable 3 --fps 12 --out " + frames.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (int i = 0; i < 3; ++i) EXPECT_EQ(pngSize(frames / ("frame_00000" + std::to_string(i) + ".png")), std::make_pair(24, 24));
    EXPECT_FALSE(std::filesystem::exists(frames / "frame_000003.png"));
    EXPECT_NE(readText(frames / "frame_000000.png"), readText(frames / "frame_000001.png")) << "the camera turns";
    // What ffmpeg was handed: run in the frames' folder, the list of this run's three frames, the rate, the temporary name.
    std::string args = readText(log);
    EXPECT_EQ(args.substr(0, args.find('\n')), std::filesystem::canonical(frames).string());
    EXPECT_NE(args.find("\n-f\nconcat\n-i\n.frames.ffconcat\n"), std::string::npos) << args;
    EXPECT_NE(args.find("\nfps=12,pad=ceil(iw/2)*2:ceil(ih/2)*2\n"), std::string::npos) << args;
    EXPECT_NE(args.find((std::filesystem::absolute(frames) / ".turntable.mp4.partial").string()), std::string::npos) << args;
    std::string list = readText(log.string() + ".list");
    EXPECT_NE(list.find("file 'frame_000000.png'\nduration 0.083333\nfile 'frame_000001.png'"), std::string::npos) << list;
    EXPECT_EQ(list.find("frame_000005"), std::string::npos) << "a stale frame is not in the movie";
    EXPECT_EQ(readText(frames / "turntable.mp4"), "movie\n");
    EXPECT_FALSE(std::filesystem::exists(frames / ".turntable.mp4.partial"));
    EXPECT_FALSE(std::filesystem::exists(frames / ".frames.ffconcat"));

    // ffmpeg fails: exit 3, the frames stay, no movie and nothing partial.
    auto failing = writeFakeFfmpeg(dir / "failing-bin", 1);
    std::filesystem::remove(frames / "turntable.mp4");
    Invocation f = runWith("PATH=" + failing.string() + ":$PATH FAKE_FFMPEG_LOG=" + log.string(),
                           "render --scene " + scene + " --turntable 2 --out " + frames.string());
    EXPECT_EQ(f.exitCode, 3) << f.output;
    EXPECT_NE(f.output.find("ffmpeg failed"), std::string::npos) << f.output;
    EXPECT_FALSE(std::filesystem::exists(frames / "turntable.mp4"));
    EXPECT_FALSE(std::filesystem::exists(frames / ".turntable.mp4.partial"));
    EXPECT_TRUE(std::filesystem::exists(frames / "frame_000001.png"));

    // No ffmpeg at all: the frames, and a sentence saying so.
    Invocation none = runWith("PATH=/nonexistent", "render --scene " + scene + " --turntable 2 --out " + frames.string());
    EXPECT_EQ(none.exitCode, 0) << none.output;
    EXPECT_NE(none.output.find("no ffmpeg on PATH"), std::string::npos) << none.output;
    EXPECT_FALSE(std::filesystem::exists(frames / "turntable.mp4"));

    Invocation png = run("render --scene " + scene + " --turntable 2 --out " + (dir / "x.png").string());
    EXPECT_EQ(png.exitCode, 2) << png.output;
    EXPECT_NE(png.output.find("--out"), std::string::npos) << png.output;
}

TEST(MovieCli, ReplayMakesItsMovieTheSameWay) {
    auto dir = scratch("replay");
    auto scene = writeBallScene(dir).string();
    auto session = dir / "session.jsonl";
    ASSERT_EQ(run("record --scene " + scene + " --out " + session.string() + " --synthetic spacemouse --frames 5 --fps 10").exitCode, 0);
    auto fake = writeFakeFfmpeg(dir / "bin");
    auto log = dir / "ffmpeg.log";
    Invocation r = runWith("PATH=" + fake.string() + ":$PATH FAKE_FFMPEG_LOG=" + log.string(),
                           "replay " + session.string() + " --out " + (dir / "out").string() + " --every 2 --mp4");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::string list = readText(log.string() + ".list");
    // Frames 0, 2, 4 of a 10 fps session, every 2nd: 5 fps.
    EXPECT_NE(list.find("file 'frame_000000.png'\nduration 0.200000\nfile 'frame_000002.png'\nduration 0.200000\nfile 'frame_000004.png'"),
              std::string::npos) << list;
    EXPECT_EQ(readText(dir / "out" / "replay.mp4"), "movie\n");
    Invocation noOut = run("replay " + session.string() + " --mp4");
    EXPECT_EQ(noOut.exitCode, 2) << noOut.output;
    Invocation noFfmpeg = runWith("PATH=/nonexistent", "replay " + session.string() + " --out " + (dir / "o2").string() + " --mp4");
    EXPECT_EQ(noFfmpeg.exitCode, 3) << noFfmpeg.output;
    EXPECT_NE(noFfmpeg.output.find("ffmpeg"), std::string::npos) << noFfmpeg.output;
}

TEST(GpuCli, InfoListsTheDevicesAndTheContextAndABadIndexIsExitTwo) {
    Invocation info = run("info --gl");
    ASSERT_EQ(info.exitCode, 0) << info.output;
    for (const char* line : {"EGL platforms", "EGL devices", "context ", "GL_RENDERER", "GL_VERSION", "--gpu automatic tries"})
        EXPECT_NE(info.output.find(line), std::string::npos) << line << "\n" << info.output;
    auto dir = scratch("gpu");
    auto scene = writeBallScene(dir).string();
    Invocation bad = run("render --scene " + scene + " --out " + (dir / "bad.png").string() + " --gpu 7");
    EXPECT_EQ(bad.exitCode, 2) << bad.output;
    EXPECT_NE(bad.output.find("--gpu"), std::string::npos) << bad.output;
    EXPECT_NE(bad.output.find("device"), std::string::npos) << "the error lists the devices: " << bad.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.png"));
    EXPECT_EQ(run("bench raycast --scene " + scene + " --gpu seven").exitCode, 2);
    EXPECT_EQ(run("info --gl --gpu 7").exitCode, 2);
    Invocation software = run("render --scene " + scene + " --out " + (dir / "sw.png").string() + " --gpu llvmpipe");
    EXPECT_EQ(software.exitCode, 0) << software.output;
    // On this machine Mesa lists its software renderer as device 0: the device platform renders the same PNG.
    if (info.output.find("  0: software") != std::string::npos) {
        Invocation device = run("render --scene " + scene + " --out " + (dir / "dev.png").string() + " --gpu 0");
        ASSERT_EQ(device.exitCode, 0) << device.output;
        Invocation surfaceless = run("render --scene " + scene + " --out " + (dir / "sl.png").string() + " --gpu surfaceless");
        ASSERT_EQ(surfaceless.exitCode, 0) << surfaceless.output;
        EXPECT_EQ(readText(dir / "dev.png"), readText(dir / "sl.png"));
    }
}

TEST(StereoCli, TheBenchWritesItsTables) {
    auto dir = scratch("bench");
    auto scene = writeBallScene(dir).string();
    auto json = dir / "stereo.json";
    Invocation r = run("bench stereo --scene " + scene + " --size 32x32 --modes solid,phong --stride 1 --json " + json.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("stereo consistency per shading mode"), std::string::npos) << r.output;
    std::string text = readText(json);
    EXPECT_NE(text.find("\"phong\""), std::string::npos) << text;
    EXPECT_NE(text.find("\"convergence_mm\""), std::string::npos) << text;
}

}  // namespace
