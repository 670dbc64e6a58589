#pragma once
// Movies: a PNG sequence in a folder (frame_NNNNNN.png, written atomically one by one) and, when ffmpeg is on
// PATH, an MP4 made from it. `render --turntable` and `replay --out ... --mp4` share these, so both name their
// frames and call ffmpeg the same way.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace curette {

// "frame_000012.png": the name of frame `index` of a sequence.
std::string movieFrameName(std::size_t index);

// The camera azimuth of turntable frame `i` of `count`: `startDeg` + 360 i / count (the last frame stops one
// step short of the first, so the movie loops without a repeated frame).
double turntableAzimuthDeg(double startDeg, int i, int count);

// The executable `program` in the directories of `pathVariable` (PATH's form, ':'-separated); nullopt when
// none is there.
std::optional<std::filesystem::path> findProgram(const std::string& program, const std::string& pathVariable);

// The concat list ffmpeg reads: exactly `frames` (names in the frames' folder), in order, each shown 1 / fps s.
// An explicit list, not a glob: frames a previous run left in the folder stay out of the movie, and the gaps
// replay --every leaves in the numbering do not matter.
std::string ffconcatList(const std::vector<std::string>& frames, double fps);

// The arguments (after the program name) ffmpeg gets, run in the frames' folder, to turn the frames `list`
// (ffconcatList's file) names into H.264 MP4 at `fps`, written to `output`: padded to even sizes (yuv420p
// needs them), yuv420p so every player shows it, the index at the front for streaming.
std::vector<std::string> ffmpegArguments(const std::string& list, double fps, const std::filesystem::path& output);

// Encodes `frames` (files in `framesDir`) into `mp4` with the ffmpeg found on PATH: written to a temporary file
// beside it and renamed, so a failed run leaves no partial movie. Returns false (and writes nothing) when there
// is no ffmpeg on PATH; throws SystemError when ffmpeg fails.
bool encodeMovie(const std::filesystem::path& framesDir, const std::vector<std::string>& frames, double fps,
                 const std::filesystem::path& mp4);

// Whether encodeMovie would find an ffmpeg (PATH as the process has it).
bool ffmpegAvailable();

}  // namespace curette
