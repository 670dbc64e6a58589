// A drilling session as a user records and replays it: the shipped head-drill session (a SpaceMouse moving a
// 4 mm burr over the head, drilling for 43 frames, one undo and one redo) replays, following the recorded
// poses or re-deriving them from the reports, to the removal `record` printed, with CAO == LAO on the rendered
// frames and the same image hashes both ways; and the report counts the drilled removal at any frame.
#include "tests/tools/run_curette.h"
#include "tests/tools/tool_test_support.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <regex>

namespace curette::testing {
namespace {

std::vector<std::string> frameHashes(const std::string& output) {
    std::vector<std::string> hashes;
    std::regex line("frame +([0-9]+) .* ([0-9a-f]{16})");
    for (auto it = std::sregex_iterator(output.begin(), output.end(), line); it != std::sregex_iterator(); ++it) hashes.push_back((*it)[2]);
    return hashes;
}

TEST(DrillSession, RecordedDrillingReplaysToTheSameRemovalAndImages) {
    const std::string scene = std::string(CURETTE_SOURCE_DIR) + "/assets/scenes/head-drill.json";
    auto dir = freshScratchFolder("curette-drill", "session");
    const std::string session = (dir / "drill.jsonl").string();
    Invocation record = runCurette("record --scene " + scene + " --out " + session +
                                   " --synthetic spacemouse --frames 40 --drill 2-30 --undo 33 --redo 36 --size 96x96");
    ASSERT_EQ(record.exitCode, 0) << record.output;
    std::string recorded = removalDigest(record.output);
    ASSERT_FALSE(recorded.empty()) << "record must say what it drilled: " << record.output;

    Invocation followed = runCurette("replay " + session + " --check --every 13");
    ASSERT_EQ(followed.exitCode, 0) << followed.output;
    EXPECT_EQ(removalDigest(followed.output), recorded);
    EXPECT_NE(followed.output.find("CAO == LAO on 4 of 4 checked frames"), std::string::npos) << followed.output;
    Invocation derived = runCurette("replay " + session + " --from-reports --check --every 13");
    ASSERT_EQ(derived.exitCode, 0) << derived.output;
    EXPECT_EQ(removalDigest(derived.output), recorded);
    EXPECT_NE(derived.output.find("identical to the recorded ones"), std::string::npos) << derived.output;
    EXPECT_EQ(frameHashes(followed.output), frameHashes(derived.output));
    EXPECT_EQ(frameHashes(followed.output).size(), 4u);

    // The session file says what was drilled and undone.
    std::string text = readTextFile(session);
    EXPECT_NE(text.find("\"drill\":[{\"mesh\":0,\"erase\":false}]"), std::string::npos);
    EXPECT_NE(text.find("\"drill_history\":[\"undo\"]"), std::string::npos);
    EXPECT_NE(text.find("\"drill_history\":[\"redo\"]"), std::string::npos);

    // The report at a frame before drilling, at its end, after the undo and after the redo.
    auto removedMl = [&](int frame) {
        auto out = dir / ("report-" + std::to_string(frame));
        Invocation r = runCurette("report --no-exports --session " + session + " --frame " + std::to_string(frame) + " --out " + out.string());
        EXPECT_EQ(r.exitCode, 0) << r.output;
        return nlohmann::json::parse(readTextFile(out / "report.json")).at("removed_ml").get<double>();
    };
    double before = removedMl(1), drilled = removedMl(31), undone = removedMl(34), redone = removedMl(37);
    EXPECT_GT(drilled, before + 0.1) << "the report counts the drilled removal";
    EXPECT_NEAR(undone, before, 0.05) << "undo takes the stroke back (the burr itself still counts)";
    EXPECT_NEAR(redone, drilled, 0.05) << "redo gives the stroke back (the burr has moved on)";
}

}  // namespace
}  // namespace curette::testing
