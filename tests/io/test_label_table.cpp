// Label tables (io/label_table.h): the mricron atlases as Debian ships them (mricron-data: aal.nii.txt with
// its planar .lut, the JHU tab form), Slicer's .ctbl and CSV forms, the plain `index name r g b [a]` table, the
// detection rules, generated colours, and malformed tables (errors name the line).
#include "io/label_table.h"
#include "base/error.h"
#include "tests/io/io_test_support.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <set>

namespace curette {
namespace {

const std::filesystem::path& kTemplates = test::kMricronTemplates;


// "r g b" in 0..255, readable in a failure message.
std::string rgb255(const LabelEntry* e) {
    if (!e) return "no such label";
    glm::dvec3 c = glm::round(glm::dvec3(e->rgba) * 255.0);
    return std::to_string(static_cast<int>(c.r)) + " " + std::to_string(static_cast<int>(c.g)) + " " + std::to_string(static_cast<int>(c.b));
}

TEST(LabelTable, AalNamesDropTheCodeColumnAndTakePlanarLutColours) {
    SKIP_WITHOUT_MRICRON("aal.nii.lut");
    LabelTable table = io::readLabelTable(kTemplates / "aal.nii.txt");
    ASSERT_EQ(table.entries.size(), 116u);
    EXPECT_EQ(table.entries.front().id, 1);
    EXPECT_EQ(table.entries.front().name, "Precentral_L");  // `1 Precentral_L 2001`: 2001 is the code
    ASSERT_NE(table.find(116), nullptr);
    EXPECT_EQ(table.find(116)->name, "Vermis_10");
    ASSERT_NE(table.findName("frontal_sup_orb_l"), nullptr);
    EXPECT_EQ(table.findName("frontal_sup_orb_l")->id, 5);
    // MRIcron's planar .lut (io/label_table.h), checked on the bytes: planar reading gives 1 = 2 = (204,204,204) and
    // 3 = 4 = (203,149,149).
    EXPECT_EQ(rgb255(table.find(1)), "204 204 204");
    EXPECT_EQ(rgb255(table.find(2)), "204 204 204");
    EXPECT_EQ(rgb255(table.find(3)), "203 149 149");
    EXPECT_EQ(rgb255(table.find(4)), "203 149 149");
    EXPECT_EQ(table.find(1)->rgba.a, 1.0);
    // The left and right halves of a structure share their colour (54 _L/_R pairs; interleaved reading would
    // give equal colours to only 4 of them).
    int pairs = 0, equal = 0;
    for (const LabelEntry& e : table.entries) {
        if (!e.name.ends_with("_L")) continue;
        const LabelEntry* right = table.findName(e.name.substr(0, e.name.size() - 2) + "_R");
        if (!right) continue;
        ++pairs;
        equal += e.rgba == right->rgba;
    }
    EXPECT_EQ(pairs, 54);
    EXPECT_EQ(equal, pairs);
}

TEST(LabelTable, JhuTabFormKeepsTheWholeNameAndLabelZero) {
    SKIP_WITHOUT_MRICRON("JHU-WhiteMatter-labels-1mm.nii.txt");
    LabelTable table = io::readLabelTable(kTemplates / "JHU-WhiteMatter-labels-1mm.nii.txt");
    ASSERT_EQ(table.entries.size(), 49u);
    EXPECT_EQ(table.find(0)->name, "Unclassified");
    EXPECT_EQ(table.find(0)->rgba.a, 0.0);  // MRIcron's invisible entry 0
    EXPECT_EQ(table.find(2)->name, "Pontine_crossing_tract_(a_part_of_MCP)");
    EXPECT_EQ(table.find(48)->name, "Tapetum_L");
    EXPECT_EQ(io::detectLabelTableFormat("0\tUnclassified\r\n1\tMiddle_cerebellar_peduncle\r\n", "x.txt"),
              io::LabelTableFormat::MricronNames);
}

TEST(LabelTable, BareLutGivesNumberedLabels) {
    SKIP_WITHOUT_MRICRON("aal.nii.lut");
    LabelTable table = io::readLut(kTemplates / "aal.nii.lut");
    ASSERT_EQ(table.entries.size(), 256u);
    EXPECT_EQ(table.find(3)->name, "label 3");
    EXPECT_EQ(rgb255(table.find(3)), "203 149 149");
    EXPECT_EQ(table.find(0)->rgba.a, 0.0);
}

TEST(LabelTable, LutOfTheWrongSizeIsRefused) {
    std::filesystem::path lut = test::scratchDirectory() / "short.lut";
    test::writeBytes(lut, std::vector<std::uint8_t>(767, 1));
    test::expectInputError([&] { io::readLut(lut); }, lut.string(), "size");
}

TEST(LabelTable, CodeColumnOnlyWhenEveryLineEndsInAnInteger) {
    // Every line ends in a number: a code column (AAL, AICHA).
    LabelTable codes = io::readLabelTableText("1 G_Frontal_Sup-1 2\n2 G_Frontal_Sup-2 3\n", "aicha.nii.txt");
    EXPECT_EQ(codes.find(1)->name, "G_Frontal_Sup-1");
    // Only some do: the numbers are part of the names, as MRIcron keeps them.
    LabelTable names = io::readLabelTableText("1 Brodmann area 4\n2 Thalamus\n", "x.nii.txt");
    EXPECT_EQ(names.find(1)->name, "Brodmann area 4");
    EXPECT_EQ(names.find(2)->name, "Thalamus");
    // A names-only table without a LUT gets generated colours.
    EXPECT_EQ(names.find(2)->rgba, io::generatedLabelColor(2));
}

TEST(LabelTable, SlicerColourTable) {
    std::string text =
        "# Color table file /tmp/x.ctbl\r\n# 3 values\r\n0 Background 0 0 0 0\r\n1 left_upper_lobe 255 128 0 255\r\n"
        "2 clamped 300 -5 51\r\n";
    EXPECT_EQ(io::detectLabelTableFormat(text, "x.txt"), io::LabelTableFormat::SlicerTable);
    LabelTable table = io::readLabelTableText(text, "x.txt");
    ASSERT_EQ(table.entries.size(), 3u);
    EXPECT_EQ(table.find(1)->name, "left upper lobe");  // `_` reads as a space
    EXPECT_EQ(table.find(1)->rgba, glm::dvec4(1.0, 128.0 / 255.0, 0.0, 1.0));
    EXPECT_EQ(table.find(2)->rgba, glm::dvec4(1.0, 0.0, 0.2, 0.0));  // clamped; no alpha: 0, as Slicer
    // By extension alone.
    EXPECT_EQ(io::detectLabelTableFormat("1 a 1 2 3 4\n", "labels.ctbl"), io::LabelTableFormat::SlicerTable);
}

TEST(LabelTable, SlicerProceduralFileIsRefused) {
    test::expectInputError([] { io::readLabelTableText("# Color procedural file /x.txt\n# 2 points\n0 0 0 0\n", "x.txt"); }, "x.txt",
                           "line 1");
}

TEST(LabelTable, SlicerCsv) {
    std::string text =
        "LabelValue,Name,Color_R,Color_G,Color_B,Color_A\n0,Background,0,0,0,0\n7,\"tumour, enhancing\",255,0,0,255\n"
        "9,spared_tract,0,0,255,128\n";
    EXPECT_EQ(io::detectLabelTableFormat(text, "x.csv"), io::LabelTableFormat::SlicerCsv);
    LabelTable table = io::readLabelTableText(text, "x.csv");
    ASSERT_EQ(table.entries.size(), 3u);
    EXPECT_EQ(table.find(7)->name, "tumour, enhancing");
    EXPECT_EQ(table.find(9)->name, "spared_tract");  // CSV names are kept as written
    EXPECT_EQ(table.find(9)->rgba, glm::dvec4(0, 0, 1, 128.0 / 255.0));
    test::expectInputError([] { io::readLabelTableText("LabelValue,Name,Color_R,Color_G,Color_B\n1,a,2,3\n", "y.csv"); }, "y.csv",
                           "line 2");
    test::expectInputError([] { io::readLabelTableText("LabelValue,Title\n1,a\n", "z.csv"); }, "z.csv", "line 1");
}

TEST(LabelTable, PlainColourTable) {
    std::string text = "# my plan\n1 tumour 255 0 0\n\n2 cavity 0 255 0 128\n";
    EXPECT_EQ(io::detectLabelTableFormat(text, "plan.txt"), io::LabelTableFormat::ColorTable);
    LabelTable table = io::readLabelTableText(text, "plan.txt");
    ASSERT_EQ(table.entries.size(), 2u);
    EXPECT_EQ(table.find(1)->rgba, glm::dvec4(1, 0, 0, 1));  // no alpha: opaque
    EXPECT_EQ(table.find(2)->rgba, glm::dvec4(0, 1, 0, 128.0 / 255.0));
    EXPECT_EQ(table.find(2)->name, "cavity");
}

TEST(LabelTable, ErrorsNameTheLine) {
    test::expectInputError([] { io::readLabelTableText("1 a\n2 b\n1 c\n", "dup.txt"); }, "dup.txt", "line 3");
    test::expectInputError([] { io::readLabelTableText("1 a\nx b\n", "index.txt"); }, "index.txt", "line 2");
    test::expectInputError([] { io::readLabelTableText("1 a\n70000 b\n", "range.txt"); }, "range.txt", "line 2");
    test::expectInputError([] { io::readLabelTableText("1\n", "noname.txt"); }, "noname.txt", "line 1");
    test::expectInputError([] { io::readLabelTableText("# Color table file\n1 a b 2 3 4\n", "s.ctbl"); }, "s.ctbl", "line 2");
    test::expectInputError([] { io::readLabelTableText("# Color table file\n1 a 1 2 3 4 5\n", "s.ctbl"); }, "s.ctbl", "line 2");
    test::expectInputError([] { io::readLabelTableText("\r\n# nothing\r\n", "empty.txt"); }, "empty.txt", "labels");
    test::expectInputError([] { io::readLabelTable("/nonexistent/labels.txt"); }, "/nonexistent/labels.txt", "");
}

TEST(LabelTable, GeneratedLabelsAreDeterministicAndDistinct) {
    EXPECT_EQ(io::generatedLabelColor(0), glm::dvec4(0.0));
    EXPECT_EQ(io::generatedLabelColor(17), io::generatedLabelColor(17));
    for (int id = 1; id < 300; ++id) {
        glm::dvec4 c = io::generatedLabelColor(id);
        EXPECT_EQ(c.a, 1.0);
        for (int k = 0; k < 3; ++k) EXPECT_TRUE(c[k] >= 0.0 && c[k] <= 1.0);
        EXPECT_GT(glm::length(glm::dvec3(c) - glm::dvec3(io::generatedLabelColor(id + 1))), 0.1) << id;
    }
    LabelTable table = io::readLabelTableText("2 b 0 0 0\n", "t.txt");
    EXPECT_EQ(io::labelEntryFor(table, 2).name, "b");
    EXPECT_EQ(io::labelEntryFor(table, 5).name, "label 5");
    LabelMap map;
    map.dims = {4, 1, 1};
    map.ids = {0, 2, 9, 3};
    io::addMissingLabels(table, map);
    ASSERT_EQ(table.entries.size(), 3u);
    EXPECT_EQ(table.entries[1].id, 3);
    EXPECT_EQ(table.entries[2].name, "label 9");
    EXPECT_EQ(table.entries[2].rgba, io::generatedLabelColor(9));
}

}  // namespace
}  // namespace curette
