// Transfer functions: JSON (strict: unknown keys, types and ranges), Slicer .vp, round trip, every preset.
#include "io/transfer_function_file.h"
#include "base/error.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace curette {
namespace {

const char* kBoneVp =
    "1\n1\n0.9\n0.1\n0.2\n10\n"
    "8 -3024 0 150 0 400 0.3 2000 0.8\n"
    "4 0 1 255 1\n"
    "16 -3024 0 0 0 150 0.9 0.8 0.7 400 1 1 0.95 2000 1 1 1\n";

TEST(TransferFunctionFile, SlicerVolumePropertyIsParsed) {
    TransferFunction tf = io::parseSlicerVolumeProperty(kBoneVp, "bone.vp");
    ASSERT_EQ(tf.opacity.size(), 4u);
    EXPECT_EQ(tf.opacity[2].value, 400);
    EXPECT_EQ(tf.opacity[2].y, 0.3);
    ASSERT_EQ(tf.color.size(), 4u);
    EXPECT_EQ(tf.color[1].rgb, glm::dvec3(0.9, 0.8, 0.7));
    EXPECT_EQ(tf.material.diffuse, 0.9);
    EXPECT_EQ(tf.material.ambient, 0.1);
    EXPECT_EQ(tf.material.specular, 0.2);
    EXPECT_EQ(tf.material.specularPower, 10);
    EXPECT_FALSE(tf.hasGradientOpacity()) << "constant 1 gradient opacity changes nothing";
    EXPECT_NEAR(tf.evaluateOpacity(275), 0.15, 1e-12);
    EXPECT_EQ(tf.evaluateOpacity(-5000), 0.0) << "clamped below the first point";
    EXPECT_EQ(tf.evaluateOpacity(9000), 0.8) << "clamped above the last point";
    // CRLF line ends and blank lines are fine.
    std::string crlf;
    for (char c : std::string(kBoneVp)) crlf += c == '\n' ? std::string("\r\n\r\n") : std::string(1, c);
    EXPECT_EQ(io::parseSlicerVolumeProperty(crlf, "crlf.vp").opacity.size(), 4u);
}

void expectVpError(const std::string& text, const std::string& field) {
    try {
        io::parseSlicerVolumeProperty(text, "bad.vp");
        FAIL() << "expected an error naming " << field;
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), field) << e.what();
    }
}

TEST(TransferFunctionFile, MalformedVpNamesTheLine) {
    expectVpError("1\n1\n0.9\n", "lines");
    expectVpError("1\n1\n0.9\n0.1\n0.2\n10\n6 0 0 1 1\n2 0 1\n4 0 1 1 1\n", "line 7 (scalar opacity)");
    expectVpError("1\n1\n0.9\n0.1\n0.2\n10\n3 0 0 1\n2 0 1\n4 0 1 1 1\n", "line 7 (scalar opacity)");
    expectVpError("1\n1\n0.9\n0.1\n0.2\n10\n4 0 0 1 x\n2 0 1\n4 0 1 1 1\n", "line 7 (scalar opacity)");
    expectVpError("1\n1\nabc\n0.1\n0.2\n10\n4 0 0 1 1\n2 0 1\n4 0 1 1 1\n", "line 3 (diffuse)");
    expectVpError("1\n1\n0.9\n0.1\n0.2\n10\n4 0 0 1 1\n2 0 1\n5 0 1 1 1 1\n", "line 9 (colour)");
    expectVpError("1\n1\n0.9\n0.1\n0.2\n10\n4 5 0 1 1\n2 0 1\n4 0 1 1 1\n", "opacity[1]");  // unsorted
    expectVpError("1\n1\n0.9\n0.1\n0.2\n10\n4 0 0 1 1.5\n2 0 1\n4 0 1 1 1\n", "opacity[1]");  // alpha > 1
    // Material out of range: a specular power of 0 (the shader's pow(0, 0) is undefined) or below, and
    // negative or huge coefficients.
    expectVpError("1\n1\n0.9\n0.1\n0.2\n0\n4 0 0 1 1\n2 0 1\n4 0 1 1 1\n", "line 6 (specular power)");
    expectVpError("1\n1\n0.9\n0.1\n0.2\n-3\n4 0 0 1 1\n2 0 1\n4 0 1 1 1\n", "line 6 (specular power)");
    expectVpError("1\n1\n-0.9\n0.1\n0.2\n10\n4 0 0 1 1\n2 0 1\n4 0 1 1 1\n", "line 3 (diffuse)");
    expectVpError("1\n1\n0.9\n0.1\n200\n10\n4 0 0 1 1\n2 0 1\n4 0 1 1 1\n", "line 5 (specular)");
}

TEST(TransferFunctionFile, JsonRoundTripAndStrictErrors) {
    TransferFunction tf = io::parseSlicerVolumeProperty(kBoneVp, "bone.vp");
    std::string json = io::writeTransferFunctionJson(tf);
    TransferFunction back = io::parseTransferFunctionJsonText(json, "round.json");
    ASSERT_EQ(back.opacity.size(), tf.opacity.size());
    for (double v : {-4000.0, 0.0, 200.0, 399.0, 1000.0, 3000.0}) {
        EXPECT_EQ(back.evaluateOpacity(v), tf.evaluateOpacity(v));
        EXPECT_EQ(back.evaluateColor(v), tf.evaluateColor(v));
    }
    auto expectError = [](const std::string& text, const std::string& field) {
        try {
            io::parseTransferFunctionJsonText(text, "bad.json");
            FAIL() << "expected an error naming " << field;
        } catch (const InputError& e) {
            EXPECT_EQ(e.field(), field) << e.what();
        }
    };
    expectError(R"({"color": [[0,1,1,1]], "opacity": [[0,0]], "colour": 1})", "colour");
    expectError(R"({"color": [[0,1,1,1]]})", "opacity");
    expectError(R"({"color": [[0,1,1,1]], "opacity": [[0,1.5]]})", "opacity[0]");
    expectError(R"({"color": [[0,1,1,"red"]], "opacity": [[0,1]]})", "color[0][3]");
    expectError(R"({"color": [[0,1,1]], "opacity": [[0,1]]})", "color[0]");
    expectError(R"({"color": [[5,1,1,1],[1,1,1,1]], "opacity": [[0,1]]})", "color[1]");
    expectError(R"({"color": [[0,1,1,1]], "opacity": [[0,1]], "material": {"shine": 2}})", "material.shine");
    expectError(R"({"color": [[0,1,1,1]], "opacity": [[0,1]], "unit_length_mm": -1})", "unit_length_mm");
    expectError(R"({"color": [[0,1,1,1]], "opacity": [[0,1]],)", "line 1, column 43");
}

TEST(TransferFunctionFile, EveryShippedPresetLoads) {
    int presets = 0;
    for (const auto& entry : std::filesystem::directory_iterator(std::string(CURETTE_SOURCE_DIR) + "/assets/tf")) {
        std::string extension = entry.path().extension().string();
        if (extension != ".json" && extension != ".vp") continue;
        TransferFunction tf = io::readTransferFunction(entry.path());
        EXPECT_FALSE(tf.opacity.empty()) << entry.path();
        ++presets;
    }
    EXPECT_GE(presets, 4);
    // The bone preset's JSON and .vp versions agree.
    TransferFunction json = io::readTransferFunction(std::string(CURETTE_SOURCE_DIR) + "/assets/tf/ct_bone.json");
    TransferFunction vp = io::readTransferFunction(std::string(CURETTE_SOURCE_DIR) + "/assets/tf/ct_bone.vp");
    for (double v = -1200; v <= 3000; v += 37.5) {
        EXPECT_NEAR(json.evaluateOpacity(v), vp.evaluateOpacity(v), 1e-12) << v;
        EXPECT_NEAR(glm::length(json.evaluateColor(v) - vp.evaluateColor(v)), 0.0, 1e-12) << v;
    }
    EXPECT_THROW(io::readTransferFunction(std::string(CURETTE_SOURCE_DIR) + "/README.md"), InputError);
}

}  // namespace
}  // namespace curette
