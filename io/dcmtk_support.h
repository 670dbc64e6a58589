#pragma once
// What the DCMTK-based writers and readers (io/dicom_*_writer.cpp, io/dicom_reference.cpp,
// io/dicom_plan_reader.cpp) share, without DCMTK in the header: UIDs, DICOM value text, the time stamp and
// DCMTK's own logging turned off (its messages can quote attribute values, i.e. a patient's name).

#include <filesystem>
#include <string>
#include <vector>

namespace curette::io {

// A new UID under DCMTK's root (dcmGenerateUniqueIdentifier, PS3.5 9).
std::string newDicomUid();

// DCMTK logs nothing below FATAL; called before any DCMTK use.
void silenceDcmtk();

// A decimal string (DS, PS3.5 6.2) of at most 16 characters, as precise as fits.
std::string decimalString(double value);
// Values joined by '\' (PS3.5 6.4: value multiplicity).
std::string decimalStrings(const std::vector<double>& values);

// Now as DICOM DA (YYYYMMDD) and TM (HHMMSS), local time.
struct DicomDateTime {
    std::string date, time;
};
DicomDateTime dicomNow();

}  // namespace curette::io
