#!/usr/bin/python3
"""A DICOM Segmentation and the image series it references, read with pydicom (not with curette's or DCMTK's
code), for tests/tools/test_dicom_export_cli.cpp.

    read_dicom_seg.py SEG.dcm SERIES_DIR

Prints one JSON object: "problems" (every inconsistency between the SEG and the series found: SOP class,
Study, Frame of Reference, frame count, each frame's segment number, source image reference and position,
the Referenced Series Sequence), "frames", "segments" (number, label, algorithm type, category and type
codes, CIELab colour) and "voxels": [segment, x, y, z, i, j] per set pixel, (x, y, z) its frame's
ImagePositionPatient (LPS mm) and (i, j) its column and row. The binary frames are unpacked here from the
bit stream (PS3.5 8.1.1: one bit a pixel, frames not padded to bytes), since numpy is not installed.
"""
import json
import os
import sys

import pydicom

SEGMENTATION_STORAGE = "1.2.840.10008.5.1.4.1.1.66.4"


def main():
    seg = pydicom.dcmread(sys.argv[1])
    images = {}
    for name in sorted(os.listdir(sys.argv[2])):
        ds = pydicom.dcmread(os.path.join(sys.argv[2], name), stop_before_pixels=True, force=True)
        if "SOPInstanceUID" in ds:
            images[ds.SOPInstanceUID] = ds
    problems = []

    def expect(condition, text):
        if not condition:
            problems.append(text)

    expect(seg.SOPClassUID == SEGMENTATION_STORAGE, "SOPClassUID is not Segmentation Storage")
    expect(seg.Modality == "SEG", "Modality is not SEG")
    expect(seg.SegmentationType == "BINARY", "SegmentationType is not BINARY")
    expect(len(images) > 0, "no images in the series folder")
    first = next(iter(images.values()))
    expect(all(im.StudyInstanceUID == seg.StudyInstanceUID for im in images.values()), "StudyInstanceUID differs from the series'")
    expect(all(im.FrameOfReferenceUID == seg.FrameOfReferenceUID for im in images.values()), "FrameOfReferenceUID differs from the series'")
    expect(all(im.get("PatientID", "") == seg.get("PatientID", "") for im in images.values()), "PatientID differs from the series'")
    expect(seg.Rows == first.Rows and seg.Columns == first.Columns, "Rows/Columns differ from the series'")

    referenced = seg.ReferencedSeriesSequence
    expect(len(referenced) == 1 and referenced[0].SeriesInstanceUID == first.SeriesInstanceUID, "ReferencedSeriesSequence names another series")
    listed = {item.ReferencedSOPInstanceUID for item in referenced[0].ReferencedInstanceSequence} if len(referenced) else set()
    expect(listed == set(images), "ReferencedInstanceSequence does not list exactly the series' images")

    segments = []
    for s in seg.SegmentSequence:
        segments.append({
            "number": int(s.SegmentNumber),
            "label": str(s.SegmentLabel),
            "algorithm_type": str(s.SegmentAlgorithmType),
            "category": [str(s.SegmentedPropertyCategoryCodeSequence[0].CodeValue), str(s.SegmentedPropertyCategoryCodeSequence[0].CodingSchemeDesignator)],
            "type": [str(s.SegmentedPropertyTypeCodeSequence[0].CodeValue), str(s.SegmentedPropertyTypeCodeSequence[0].CodingSchemeDesignator),
                     str(s.SegmentedPropertyTypeCodeSequence[0].CodeMeaning)],
            "cielab": [int(v) for v in s.RecommendedDisplayCIELabValue],
        })
    numbers = {s["number"] for s in segments}

    frames = int(seg.NumberOfFrames)
    per_frame = seg.PerFrameFunctionalGroupsSequence
    expect(len(per_frame) == frames, "NumberOfFrames differs from the per-frame functional groups")
    rows, columns = int(seg.Rows), int(seg.Columns)
    data = seg.PixelData
    expect(len(data) * 8 >= frames * rows * columns, "PixelData is shorter than the frames")
    shared = seg.SharedFunctionalGroupsSequence[0]

    def macro(group, name):
        # A functional group macro of this frame: per frame, or shared by all (PS3.3 C.7.6.16).
        return getattr(group, name) if name in group else getattr(shared, name)

    voxels = []
    for f, group in enumerate(per_frame):
        number = int(macro(group, "SegmentIdentificationSequence")[0].ReferencedSegmentNumber)
        expect(number in numbers, "frame %d names segment %d, which is not in the SegmentSequence" % (f + 1, number))
        position = [float(v) for v in macro(group, "PlanePositionSequence")[0].ImagePositionPatient]
        source = macro(group, "DerivationImageSequence")[0].SourceImageSequence[0]
        image = images.get(source.ReferencedSOPInstanceUID)
        expect(image is not None, "frame %d's source image is not in the series" % (f + 1))
        if image is not None:
            expect(source.ReferencedSOPClassUID == image.SOPClassUID, "frame %d's source SOP class differs" % (f + 1))
            expect(max(abs(a - float(b)) for a, b in zip(position, image.ImagePositionPatient)) < 1e-3,
                   "frame %d's ImagePositionPatient is not its source image's" % (f + 1))
        base = f * rows * columns
        for j in range(rows):
            for i in range(columns):
                bit = base + j * columns + i
                if (data[bit >> 3] >> (bit & 7)) & 1:
                    voxels.append([number] + position + [i, j])
    print(json.dumps({"problems": problems, "frames": frames, "segments": segments, "voxels": voxels}))


if __name__ == "__main__":
    main()
