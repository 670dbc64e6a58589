#pragma once
// Writing small DICOM files with GDCM for the DICOM tests: CT/MR slices and enhanced multi-frame objects,
// explicit VR little endian, every attribute chosen by the test (gdcm::Writer, not gdcm::ImageWriter, which
// would fill in geometry of its own).

#include <gdcmDataElement.h>
#include <gdcmDataSet.h>
#include <gdcmFile.h>
#include <gdcmFileMetaInformation.h>
#include <gdcmItem.h>
#include <gdcmSequenceOfItems.h>
#include <gdcmTag.h>
#include <gdcmTransferSyntax.h>
#include <gdcmUIDGenerator.h>
#include <gdcmWriter.h>

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace curette::test {

inline std::string newUid() {
    gdcm::UIDGenerator generator;
    return generator.Generate();
}

struct DicomImageSpec {
    std::string sopClassUid = "1.2.840.10008.5.1.4.1.1.2";  // CT Image Storage
    std::string sopInstanceUid;                              // "": a new UID
    std::string studyUid, seriesUid;                         // required
    std::string frameOfReferenceUid;                         // "": absent
    std::string seriesNumber = "1", seriesDescription = "synthetic", modality = "CT";
    std::string patientName = "Anonymous", patientId = "0", patientBirthDate, accessionNumber;
    std::string imageType = "ORIGINAL\\PRIMARY\\AXIAL";
    int instanceNumber = 1;
    int rows = 3, columns = 4;
    glm::dvec3 position{0.0};                             // ImagePositionPatient, LPS mm
    std::array<double, 6> orientation{1, 0, 0, 0, 1, 0};  // ImageOrientationPatient
    glm::dvec2 pixelSpacing{1.0, 1.0};                    // row spacing, column spacing
    double sliceThickness = 1.0;
    int bitsStored = 16;
    bool isSigned = true;
    std::string rescaleSlope = "1", rescaleIntercept = "0";  // "": absent
    std::string gantryDetectorTilt;                          // "": absent
    // 16-bit samples, rows x columns per frame, column index fastest; stored as their low 16 bits.
    std::vector<std::int32_t> pixels;
    // Non-empty: an enhanced multi-frame object, one frame per position (PerFrameFunctionalGroupsSequence),
    // orientation, pixel spacing and rescale in the SharedFunctionalGroupsSequence (PS3.3 C.7.6.16).
    std::vector<glm::dvec3> framePositions;
};

namespace dicom_writer_detail {

inline std::string decimals(const double* values, std::size_t count) {
    std::string text;
    for (std::size_t i = 0; i < count; ++i) {
        char value[32];
        std::snprintf(value, sizeof value, "%.10g", values[i]);
        if (i) text += '\\';
        text += value;
    }
    return text;
}

inline void putText(gdcm::DataSet& dataSet, std::uint16_t group, std::uint16_t element, gdcm::VR vr, std::string value) {
    if (value.size() % 2) value.push_back(vr == gdcm::VR::UI ? '\0' : ' ');  // PS3.5 6.2: even length
    gdcm::DataElement de(gdcm::Tag(group, element));
    de.SetVR(vr);
    de.SetByteValue(value.data(), static_cast<std::uint32_t>(value.size()));
    dataSet.Replace(de);
}

inline void putUnsignedShort(gdcm::DataSet& dataSet, std::uint16_t group, std::uint16_t element, int value) {
    std::uint16_t v = static_cast<std::uint16_t>(value);
    char bytes[2];
    std::memcpy(bytes, &v, 2);  // little endian on the machines curette supports
    gdcm::DataElement de(gdcm::Tag(group, element));
    de.SetVR(gdcm::VR::US);
    de.SetByteValue(bytes, 2);
    dataSet.Replace(de);
}

inline void putSequence(gdcm::DataSet& dataSet, std::uint16_t group, std::uint16_t element, const std::vector<gdcm::DataSet>& items) {
    gdcm::SmartPointer<gdcm::SequenceOfItems> sequence = new gdcm::SequenceOfItems;
    sequence->SetLengthToUndefined();
    for (const gdcm::DataSet& nested : items) {
        gdcm::Item item;
        item.SetVLToUndefined();
        item.SetNestedDataSet(nested);
        sequence->AddItem(item);
    }
    gdcm::DataElement de(gdcm::Tag(group, element));
    de.SetVR(gdcm::VR::SQ);
    de.SetValue(*sequence);
    de.SetVLToUndefined();
    dataSet.Replace(de);
}

inline gdcm::DataSet oneElement(std::uint16_t group, std::uint16_t element, gdcm::VR vr, const std::string& value) {
    gdcm::DataSet item;
    putText(item, group, element, vr, value);
    return item;
}

}  // namespace dicom_writer_detail

// Writes one DICOM file; throws std::runtime_error when GDCM cannot.
inline void writeDicom(const std::filesystem::path& path, const DicomImageSpec& spec) {
    using namespace dicom_writer_detail;
    const bool enhanced = !spec.framePositions.empty();
    const std::size_t frames = enhanced ? spec.framePositions.size() : 1;
    if (spec.pixels.size() != static_cast<std::size_t>(spec.rows * spec.columns) * frames)
        throw std::runtime_error("writeDicom: pixels must hold rows x columns x frames samples");
    gdcm::Writer writer;
    writer.SetFileName(path.string().c_str());
    gdcm::File& file = writer.GetFile();
    file.GetHeader().SetDataSetTransferSyntax(gdcm::TransferSyntax::ExplicitVRLittleEndian);
    gdcm::DataSet& ds = file.GetDataSet();
    putText(ds, 0x0008, 0x0008, gdcm::VR::CS, spec.imageType);
    putText(ds, 0x0008, 0x0016, gdcm::VR::UI, enhanced ? "1.2.840.10008.5.1.4.1.1.2.1" : spec.sopClassUid);  // Enhanced CT
    putText(ds, 0x0008, 0x0018, gdcm::VR::UI, spec.sopInstanceUid.empty() ? newUid() : spec.sopInstanceUid);
    if (!spec.accessionNumber.empty()) putText(ds, 0x0008, 0x0050, gdcm::VR::SH, spec.accessionNumber);
    putText(ds, 0x0008, 0x0060, gdcm::VR::CS, spec.modality);
    putText(ds, 0x0008, 0x103e, gdcm::VR::LO, spec.seriesDescription);
    putText(ds, 0x0010, 0x0010, gdcm::VR::PN, spec.patientName);
    putText(ds, 0x0010, 0x0020, gdcm::VR::LO, spec.patientId);
    if (!spec.patientBirthDate.empty()) putText(ds, 0x0010, 0x0030, gdcm::VR::DA, spec.patientBirthDate);
    if (!enhanced) putText(ds, 0x0018, 0x0050, gdcm::VR::DS, decimals(&spec.sliceThickness, 1));
    if (!spec.gantryDetectorTilt.empty()) putText(ds, 0x0018, 0x1120, gdcm::VR::DS, spec.gantryDetectorTilt);
    putText(ds, 0x0020, 0x000d, gdcm::VR::UI, spec.studyUid);
    putText(ds, 0x0020, 0x000e, gdcm::VR::UI, spec.seriesUid);
    putText(ds, 0x0020, 0x0011, gdcm::VR::IS, spec.seriesNumber);
    putText(ds, 0x0020, 0x0013, gdcm::VR::IS, std::to_string(spec.instanceNumber));
    if (!spec.frameOfReferenceUid.empty()) putText(ds, 0x0020, 0x0052, gdcm::VR::UI, spec.frameOfReferenceUid);
    const std::string orientation = decimals(spec.orientation.data(), 6);
    const double spacing[2] = {spec.pixelSpacing[0], spec.pixelSpacing[1]};
    if (!enhanced) {
        const double position[3] = {spec.position.x, spec.position.y, spec.position.z};
        putText(ds, 0x0020, 0x0032, gdcm::VR::DS, decimals(position, 3));
        putText(ds, 0x0020, 0x0037, gdcm::VR::DS, orientation);
    }
    putUnsignedShort(ds, 0x0028, 0x0002, 1);
    putText(ds, 0x0028, 0x0004, gdcm::VR::CS, "MONOCHROME2");
    if (enhanced) putText(ds, 0x0028, 0x0008, gdcm::VR::IS, std::to_string(frames));
    putUnsignedShort(ds, 0x0028, 0x0010, spec.rows);
    putUnsignedShort(ds, 0x0028, 0x0011, spec.columns);
    if (!enhanced) putText(ds, 0x0028, 0x0030, gdcm::VR::DS, decimals(spacing, 2));
    putUnsignedShort(ds, 0x0028, 0x0100, 16);
    putUnsignedShort(ds, 0x0028, 0x0101, spec.bitsStored);
    putUnsignedShort(ds, 0x0028, 0x0102, spec.bitsStored - 1);
    putUnsignedShort(ds, 0x0028, 0x0103, spec.isSigned ? 1 : 0);
    if (!enhanced) {
        if (!spec.rescaleIntercept.empty()) putText(ds, 0x0028, 0x1052, gdcm::VR::DS, spec.rescaleIntercept);
        if (!spec.rescaleSlope.empty()) putText(ds, 0x0028, 0x1053, gdcm::VR::DS, spec.rescaleSlope);
    } else {
        gdcm::DataSet shared;
        putSequence(shared, 0x0020, 0x9116, {oneElement(0x0020, 0x0037, gdcm::VR::DS, orientation)});  // PlaneOrientation
        gdcm::DataSet measures;
        putText(measures, 0x0028, 0x0030, gdcm::VR::DS, decimals(spacing, 2));
        putText(measures, 0x0018, 0x0050, gdcm::VR::DS, decimals(&spec.sliceThickness, 1));
        putSequence(shared, 0x0028, 0x9110, {measures});  // PixelMeasures
        gdcm::DataSet transformation;
        putText(transformation, 0x0028, 0x1052, gdcm::VR::DS, spec.rescaleIntercept.empty() ? "0" : spec.rescaleIntercept);
        putText(transformation, 0x0028, 0x1053, gdcm::VR::DS, spec.rescaleSlope.empty() ? "1" : spec.rescaleSlope);
        putText(transformation, 0x0028, 0x1054, gdcm::VR::LO, "HU");
        putSequence(shared, 0x0028, 0x9145, {transformation});  // PixelValueTransformation
        putSequence(ds, 0x5200, 0x9229, {shared});
        std::vector<gdcm::DataSet> perFrame;
        for (const glm::dvec3& p : spec.framePositions) {
            const double position[3] = {p.x, p.y, p.z};
            gdcm::DataSet group;
            putSequence(group, 0x0020, 0x9113, {oneElement(0x0020, 0x0032, gdcm::VR::DS, decimals(position, 3))});  // PlanePosition
            perFrame.push_back(group);
        }
        putSequence(ds, 0x5200, 0x9230, perFrame);
    }
    std::vector<char> bytes(spec.pixels.size() * 2);
    for (std::size_t i = 0; i < spec.pixels.size(); ++i) {
        std::uint16_t v = static_cast<std::uint16_t>(static_cast<std::uint32_t>(spec.pixels[i]) & 0xffffu);
        std::memcpy(bytes.data() + 2 * i, &v, 2);
    }
    gdcm::DataElement pixelData(gdcm::Tag(0x7fe0, 0x0010));
    pixelData.SetVR(gdcm::VR::OW);
    pixelData.SetByteValue(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
    ds.Replace(pixelData);
    writer.SetCheckFileMetaInformation(true);  // fills group 0002 from the SOP class and instance
    if (!writer.Write()) throw std::runtime_error("writeDicom: GDCM could not write " + path.string());
}

}  // namespace curette::test
