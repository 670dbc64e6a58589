// The drilled removal kept across files (session/removal_file.h): written and read back bit for bit on the scan
// grid, refused (naming file, field and form) on another grid; a saved scene names it and every command that
// loads the scene loads it; a recording started after drilling starts from it, so its replays (following and
// re-deriving from the reports) reach the live removal; and --from-reports checks the drilling it re-derives.
#include "session/live_input.h"
#include "session/loaded_scene.h"
#include "session/plan_scene.h"
#include "session/removal_file.h"
#include "session/session_step.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "base/sha256.h"
#include "io/nifti_uint64.h"
#include "input/hid/fake_backend.h"
#include "tests/tools/run_curette.h"
#include "tests/tools/tool_test_support.h"

#include <gtest/gtest.h>

#include <bit>
#include <random>
#include <regex>

namespace curette::testing {
namespace {

// A 13 x 9 x 7 grid (bricks cut at the edges), oblique, with a drilled sphere and an erased slab in it.
plan::RemovalVolume drilledSample() {
    glm::dmat4 affine(glm::dvec4(0.0, 1.1, 0.2, 0.0), glm::dvec4(-0.9, 0.0, 0.0, 0.0), glm::dvec4(0.0, 0.1, 1.7, 0.0), glm::dvec4(-4.0, 2.5, 1.0, 1.0));
    plan::RemovalVolume removal({13, 9, 7}, affine);
    glm::dvec3 centre(affine * glm::dvec4(6.0, 4.0, 3.0, 1.0));
    removal.apply([&](glm::dvec3 w) { return glm::length(w - centre) < 4.3; }, {{0, 0, 0}, {13, 9, 7}}, false);
    removal.apply([&](glm::dvec3 w) { return std::abs(w.x - centre.x) < 0.7; }, {{0, 0, 0}, {13, 9, 7}}, true);
    return removal;
}

TEST(RemovalFile, ReadsBackBitForBit) {
    auto dir = freshScratchFolder("curette-removal", "roundtrip");
    plan::RemovalVolume removal = drilledSample();
    ASSERT_FALSE(removal.empty());
    writeRemovalFile(dir / "r.removal.nii.gz", removal);
    auto back = readRemovalFile(dir / "r.removal.nii.gz", removal.dims(), removal.indexToWorld(), "scene.json", "removal");
    EXPECT_EQ(back->digest(), removal.digest());
    EXPECT_EQ(back->storedBricks(), removal.storedBricks());
    EXPECT_EQ(back->indexToWorld(), removal.indexToWorld()) << "the scan's affine, not the file's float32 copy";
    bool partial = false;
    for (int z = 0; z < 7; ++z)
        for (int y = 0; y < 9; ++y)
            for (int x = 0; x < 13; ++x) partial = partial || (!plan::isEmpty(removal.mask({x, y, z})) && removal.mask({x, y, z}) != plan::kFullVoxelMask);
    EXPECT_TRUE(partial) << "the sample has voxels drilled in part";
    EXPECT_EQ(removalFileBeside("/a/b/plan.json"), std::filesystem::path("/a/b/plan.removal.nii.gz"));
}

// A file written with 4 x 4 x 4 sub-cells (3-D, a word per voxel: bit i + 4 j + 16 k) loads: each old
// sub-cell is its 2 x 2 x 2 new ones, so every voxel keeps its fraction; the digest it reports for a session
// header is the one written then (of the words).
TEST(RemovalFile, AFileOfFourSubCellsPerAxisLoadsAsTheSameRegion) {
    auto dir = freshScratchFolder("curette-removal", "four");
    plan::RemovalVolume sample = drilledSample();
    io::Uint64Volume old{sample.dims(), sample.indexToWorld(), 1, {}};
    std::mt19937_64 random(5);
    for (int i = 0; i < 13 * 9 * 7; ++i) old.values.push_back(i % 4 == 0 ? 0 : i % 4 == 1 ? ~std::uint64_t(0) : random());
    io::writeNiftiUint64(dir / "old.removal.nii.gz", old, "curette drilled removal: 4x4x4 bits");
    std::string digest;
    auto back = readRemovalFile(dir / "old.removal.nii.gz", sample.dims(), sample.indexToWorld(), "scene.json", "removal", &digest);
    for (int z = 0; z < 7; ++z)
        for (int y = 0; y < 9; ++y)
            for (int x = 0; x < 13; ++x) {
                std::uint64_t word = old.values[static_cast<std::size_t>((z * 9 + y) * 13 + x)];
                plan::VoxelMask m = back->mask({x, y, z});
                ASSERT_EQ(plan::drilledCells(m), 8 * std::popcount(word));
                for (int k = 0; k < 8; ++k)
                    for (int j = 0; j < 8; ++j)
                        for (int i = 0; i < 8; ++i)
                            ASSERT_EQ((m[static_cast<std::size_t>(k)] >> (j * 8 + i)) & 1u, (word >> ((k / 2 * 4 + j / 2) * 4 + i / 2)) & 1u);
            }
    // Version 6's digest: each drilled voxel's brick-order index and word.
    Sha256 hash;
    std::vector<std::pair<std::uint64_t, std::uint64_t>> records;
    for (int z = 0; z < 7; ++z)
        for (int y = 0; y < 9; ++y)
            for (int x = 0; x < 13; ++x) {
                std::uint64_t word = old.values[static_cast<std::size_t>((z * 9 + y) * 13 + x)];
                glm::ivec3 v(x, y, z);
                if (word) records.push_back({std::uint64_t(back->brickNumber(v / 4)) * 64 + static_cast<std::uint64_t>(((z % 4) * 4 + y % 4) * 4 + x % 4), word});
            }
    std::sort(records.begin(), records.end());
    for (const auto& r : records) {
        std::uint64_t record[2] = {r.first, r.second};
        hash.update(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(record), sizeof record));
    }
    EXPECT_EQ(digest, hash.hexDigest());
    EXPECT_NE(digest, back->digest());
}

TEST(RemovalFile, AnotherGridOrNoFileIsAnInputErrorNamingIt) {
    auto dir = freshScratchFolder("curette-removal", "refused");
    plan::RemovalVolume removal = drilledSample();
    const std::filesystem::path file = dir / "r.removal.nii.gz";
    writeRemovalFile(file, removal);
    auto expectError = [&](auto read, const std::string& where, const std::string& field) {
        try {
            read();
            ADD_FAILURE() << "accepted";
        } catch (const InputError& e) {
            EXPECT_EQ(e.file(), where) << e.what();
            EXPECT_EQ(e.field(), field) << e.what();
        }
    };
    expectError([&] { readRemovalFile(file, {13, 9, 8}, removal.indexToWorld(), "scene.json", "removal"); }, file.string(), "dim");
    glm::dmat4 moved = removal.indexToWorld();
    moved[3].x += 0.5;
    expectError([&] { readRemovalFile(file, removal.dims(), moved, "scene.json", "removal"); }, file.string(), "srow_x/y/z");
    expectError([&] { readRemovalFile(dir / "none.nii.gz", removal.dims(), removal.indexToWorld(), "scene.json", "removal"); }, "scene.json", "removal");
}

const nlohmann::json kDrillScene = nlohmann::json::parse(R"({"clip_meshes": [{"name": "burr", "mesh": {"shape": "sphere", "radius_mm": 7}, "position_mm": [31, 31, 40]}]})");

// A scene saved after drilling writes its removal beside it; report and render load it with the scene.
TEST(DrillPersistence, ASavedSceneLoadsItsRemoval) {
    auto dir = freshScratchFolder("curette-removal", "saved");
    std::filesystem::path scene = writeNoisyBallScene(dir, kDrillScene);
    Invocation rec = runCurette("record --scene " + scene.string() + " --out " + (dir / "s.jsonl").string() + " --synthetic spacemouse --frames 12 --drill 1-9");
    ASSERT_EQ(rec.exitCode, 0) << rec.output;
    Invocation saved = runCurette("replay " + (dir / "s.jsonl").string() + " --no-render --from-reports --save-scene " + (dir / "saved.json").string());
    ASSERT_EQ(saved.exitCode, 0) << saved.output;
    std::string digest = removalDigest(saved.output);
    ASSERT_FALSE(digest.empty()) << saved.output;
    EXPECT_EQ(digest, removalDigest(rec.output));
    nlohmann::json json = nlohmann::json::parse(readTextFile(dir / "saved.json"));
    ASSERT_EQ(json.value("removal", ""), "saved.removal.nii.gz");
    LoadedScene loaded = loadSceneWithVolume(dir / "saved.json");
    ASSERT_TRUE(loaded.removal);
    EXPECT_EQ(loaded.removal->digest(), digest) << "bit for bit";

    // The same scene without the key: the report counts less removed, the image differs.
    json.erase("removal");
    writeFileAtomically(dir / "bare.json", json.dump(2));
    auto removedMl = [&](const std::string& name) {
        Invocation r = runCurette("report --no-exports --scene " + (dir / (name + ".json")).string() + " --out " + (dir / ("report-" + name)).string());
        EXPECT_EQ(r.exitCode, 0) << r.output;
        return nlohmann::json::parse(readTextFile(dir / ("report-" + name) / "report.json")).at("removed_ml").get<double>();
    };
    EXPECT_GT(removedMl("saved"), removedMl("bare") + 0.05);
    for (const char* name : {"saved", "bare"})
        ASSERT_EQ(runCurette("render --scene " + (dir / (std::string(name) + ".json")).string() + " --out " + (dir / (std::string(name) + ".png")).string()).exitCode, 0);
    EXPECT_NE(readPng(dir / "saved.png").rgba, readPng(dir / "bare.png").rgba) << "render draws the scene's removal";

    // A removal on another grid, and a missing one, are refused naming the scene's key or the file.
    json["removal"] = "missing.removal.nii.gz";
    writeFileAtomically(dir / "missing.json", json.dump(2));
    Invocation missing = runCurette("render --scene " + (dir / "missing.json").string() + " --out " + (dir / "missing.png").string());
    EXPECT_NE(missing.exitCode, 0);
    EXPECT_NE(missing.output.find("removal"), std::string::npos) << missing.output;
    EXPECT_NE(missing.output.find("missing.removal.nii.gz"), std::string::npos) << missing.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "missing.png")) << "no partial output";
    plan::RemovalVolume other({16, 16, 16}, glm::dmat4(2.0));
    writeRemovalFile(dir / "other.removal.nii.gz", other);
    json["removal"] = "other.removal.nii.gz";
    writeFileAtomically(dir / "other.json", json.dump(2));
    Invocation wrong = runCurette("report --no-exports --scene " + (dir / "other.json").string() + " --out " + (dir / "report-other").string());
    EXPECT_NE(wrong.exitCode, 0);
    EXPECT_NE(wrong.output.find("other.removal.nii.gz"), std::string::npos) << wrong.output;
    EXPECT_NE(wrong.output.find("32 x 32 x 32"), std::string::npos) << "the expected grid: " << wrong.output;
}

// Drilling from the keyboard, then F9 mid-run, then a second stroke, undo, an undo with nothing left since
// the recording started, and redo: both replays reach the live removal, and from-reports finds the same drilling.
TEST(DrillPersistence, ARecordingStartedAfterDrillingStartsFromItsRemoval) {
    auto dir = freshScratchFolder("curette-removal", "late");
    std::filesystem::path scenePath = writeNoisyBallScene(dir, kDrillScene);
    LoadedScene loaded = loadSceneWithVolume(scenePath);
    VolumeGeometry geometry{loaded.volume.dims, loaded.volume.indexToWorld};
    SessionStep step(InteractionState::fromScene(loaded.scene), initialFrame(loaded.scene, geometry));
    step.attachRemoval(loaded.volume.dims, loaded.volume.indexToWorld, loaded.removal.get());
    LiveInput live(std::make_unique<input::FakeHidBackend>(std::make_shared<input::FakeHidBackend::Ports>()), input::defaultMapping(), 40.0, 60.0);
    std::unique_ptr<LiveRecording> recording;
    std::string atStart;
    for (int f = 0; f < 36; ++f) {
        input::KeyboardMouseState keys;
        if ((f >= 2 && f <= 8) || (f >= 16 && f <= 22)) keys.press(input::Key::Drill);
        if (f >= 3 && f <= 12) keys.press(input::Key::W);
        if (f >= 16 && f <= 22) keys.press(input::Key::D);
        if (f == 26 || f == 29) keys.press(input::Key::Undo);
        if (f == 32) keys.press(input::Key::Redo);
        double now = f / 30.0;
        InputFrame in = live.step(now, keys, 1 / 30.0, static_cast<int>(step.state().meshes.size()));
        step.apply(in.actions, 480);
        if (recording) recording->addFrame(now, 1 / 30.0, {48, 48}, step.frame().camera, step.state(), keys, in);
        if (f == 12) {
            recording = std::make_unique<LiveRecording>(dir / "late.jsonl", scenePath.string(), step.state(), live, now);
            atStart = step.state().removal->digest();
        }
        if (f == 29) {
            EXPECT_TRUE(step.state().appliedHistory.empty()) << "the first stroke was made before the recording: not undone";
        }
    }
    recording->finish();
    const std::string liveDigest = step.state().removal->digest();
    Session session = readSession(dir / "late.jsonl", false);
    EXPECT_EQ(session.header.version, kSessionVersion);
    EXPECT_EQ(session.header.removal, "late.removal.nii.gz");
    EXPECT_EQ(session.header.removalDigest, atStart);
    EXPECT_NE(atStart, liveDigest) << "the recording drilled too";

    Invocation followed = runCurette("replay " + (dir / "late.jsonl").string() + " --every 40");
    ASSERT_EQ(followed.exitCode, 0) << followed.output;
    EXPECT_EQ(removalDigest(followed.output), liveDigest);
    Invocation derived = runCurette("replay " + (dir / "late.jsonl").string() + " --from-reports --check --every 40");
    ASSERT_EQ(derived.exitCode, 0) << derived.output;
    EXPECT_EQ(removalDigest(derived.output), liveDigest);
    EXPECT_NE(derived.output.find("poses and drilling from reports: identical"), std::string::npos) << derived.output;

    // A session whose removal file was replaced is refused, naming it.
    writeRemovalFile(dir / "late.removal.nii.gz", plan::RemovalVolume(loaded.volume.dims, loaded.volume.indexToWorld));
    Invocation swapped = runCurette("replay " + (dir / "late.jsonl").string() + " --no-render --from-reports");
    EXPECT_NE(swapped.exitCode, 0);
    EXPECT_NE(swapped.output.find("late.removal.nii.gz"), std::string::npos) << swapped.output;
}

// From version 6 the frame's "drill" is what the keys and devices did: --from-reports re-derives it and says so
// when the record disagrees.
TEST(DrillPersistence, FromReportsChecksTheDrillingItDerives) {
    auto dir = freshScratchFolder("curette-removal", "derived");
    std::filesystem::path scene = writeNoisyBallScene(dir, kDrillScene);
    const std::string session = (dir / "s.jsonl").string();
    ASSERT_EQ(runCurette("record --scene " + scene.string() + " --out " + session + " --synthetic spacemouse --frames 12 --drill 2-5 --undo 8").exitCode, 0);
    std::string text = readTextFile(session);
    EXPECT_NE(text.find("\"drill\":[{\"mesh\":0,\"erase\":false}]"), std::string::npos) << "recorded as applied";
    Invocation ok = runCurette("replay " + session + " --from-reports --no-render");
    EXPECT_EQ(ok.exitCode, 0) << ok.output;
    // The record says erase where the keys drilled: the derived drilling differs.
    std::string tampered = std::regex_replace(text, std::regex("\"erase\":false"), "\"erase\":true", std::regex_constants::format_first_only);
    writeFileAtomically(dir / "t.jsonl", tampered);
    Invocation bad = runCurette("replay " + (dir / "t.jsonl").string() + " --from-reports --no-render");
    EXPECT_NE(bad.exitCode, 0) << bad.output;
    EXPECT_NE(bad.output.find("DIFFERENT"), std::string::npos) << bad.output;
}

}  // namespace
}  // namespace curette::testing
