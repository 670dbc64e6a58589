// Movies (tools/movie.h: frame names, the turntable's azimuths, the list and command line ffmpeg gets, finding
// it on PATH) and the --gpu option (tools/command_line.h), on made-up device lists.
#include "tools/command_line.h"
#include "tools/movie.h"
#include "base/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sys/stat.h>
#include <unistd.h>

namespace curette {
namespace {

TEST(Movie, FramesAreNamedInOrderAndTheTurntableStopsOneStepShortOfAFullTurn) {
    EXPECT_EQ(movieFrameName(0), "frame_000000.png");
    EXPECT_EQ(movieFrameName(1234), "frame_001234.png");
    EXPECT_DOUBLE_EQ(turntableAzimuthDeg(35, 0, 8), 35);
    EXPECT_DOUBLE_EQ(turntableAzimuthDeg(35, 2, 8), 125);
    EXPECT_DOUBLE_EQ(turntableAzimuthDeg(35, 7, 8), 350);   // 395 would repeat frame 0
}

TEST(Movie, FfmpegGetsExactlyTheFramesOfTheRunAtTheRequestedRate) {
    std::string list = ffconcatList({"frame_000000.png", "frame_000010.png", "it's.png"}, 25);
    EXPECT_EQ(list,
              "ffconcat version 1.0\n"
              "file 'frame_000000.png'\nduration 0.040000\n"
              "file 'frame_000010.png'\nduration 0.040000\n"
              "file 'it'\\''s.png'\nduration 0.040000\n");
    std::vector<std::string> a = ffmpegArguments(".frames.ffconcat", 25, "/out/.turntable.mp4.partial");
    auto after = [&](const std::string& option) {
        auto it = std::find(a.begin(), a.end(), option);
        return it != a.end() && it + 1 != a.end() ? *(it + 1) : std::string("(missing)");
    };
    EXPECT_EQ(after("-f"), "concat");
    EXPECT_EQ(after("-i"), ".frames.ffconcat");
    EXPECT_EQ(after("-vf"), "fps=25,pad=ceil(iw/2)*2:ceil(ih/2)*2");
    EXPECT_EQ(after("-c:v"), "libx264");
    EXPECT_EQ(after("-pix_fmt"), "yuv420p");
    EXPECT_NE(std::find(a.begin(), a.end(), "-y"), a.end());
    EXPECT_NE(std::find(a.begin(), a.end(), "-nostdin"), a.end()) << "ffmpeg must not wait for the terminal";
    ASSERT_GE(a.size(), 3u);
    EXPECT_EQ(a[a.size() - 3], "-f");
    EXPECT_EQ(a[a.size() - 2], "mp4") << "the temporary name does not end in .mp4, so the muxer is named";
    EXPECT_EQ(a.back(), "/out/.turntable.mp4.partial");
}

TEST(Movie, FindsAnExecutableOnThePathAndNothingElse) {
    auto dir = std::filesystem::temp_directory_path() / ("curette-movie-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir / "a");
    std::filesystem::create_directories(dir / "b");
    std::ofstream(dir / "a" / "ffmpeg") << "#!/bin/sh\n";   // not executable
    std::ofstream(dir / "b" / "ffmpeg") << "#!/bin/sh\n";
    ::chmod((dir / "b" / "ffmpeg").c_str(), 0755);
    std::string path = (dir / "a").string() + ":" + (dir / "b").string();
    EXPECT_EQ(findProgram("ffmpeg", path), dir / "b" / "ffmpeg");
    EXPECT_EQ(findProgram("ffmpeg", (dir / "a").string()), std::nullopt);
    EXPECT_EQ(findProgram("ffmpeg", ""), std::nullopt);
    std::filesystem::remove_all(dir);
}

TEST(GpuOption, NamesADeviceOrASoftwareRendererAndAWrongIndexListsTheDevices) {
    gl::EglPlatforms p;
    p.deviceEnumeration = p.platformDevice = true;
    gl::EglDevice hardware;
    hardware.index = 0;
    hardware.eglVendor = "NVIDIA";
    hardware.eglVersion = "1.5";
    gl::EglDevice software;
    software.index = 1;
    software.software = true;
    software.eglVendor = "Mesa Project";
    software.eglVersion = "1.5";
    p.devices = {hardware, software};
    EXPECT_EQ(parseGpuChoice("0", p), (gl::GpuChoice{gl::GpuChoice::Kind::Device, 0}));
    EXPECT_EQ(parseGpuChoice("1", p), (gl::GpuChoice{gl::GpuChoice::Kind::Device, 1}));
    EXPECT_EQ(parseGpuChoice("llvmpipe", p), (gl::GpuChoice{gl::GpuChoice::Kind::Software, -1}));
    EXPECT_EQ(parseGpuChoice("surfaceless", p), (gl::GpuChoice{gl::GpuChoice::Kind::Surfaceless, -1}));
    for (std::string bad : {"2", "-1", "7", "gpu0", ""}) {
        try {
            parseGpuChoice(bad, p);
            ADD_FAILURE() << "--gpu " << bad << " accepted";
        } catch (const InputError& e) {
            EXPECT_EQ(e.field(), "--gpu");
            EXPECT_NE(e.expected().find("0: hardware, NVIDIA (EGL 1.5)"), std::string::npos) << e.what();
            EXPECT_NE(e.expected().find("1: software, Mesa Project"), std::string::npos) << e.what();
        }
    }
    CommandLine none({}, withGpuOption({}));
    EXPECT_EQ(gpuChoice(none), gl::GpuChoice{}) << "no --gpu: automatic";
}

}  // namespace
}  // namespace curette
