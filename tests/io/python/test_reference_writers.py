"""Round trips through the reference writers of each format, at test time with random content:
nibabel (NIfTI-1/-2, .nii, .nii.gz, .hdr/.img) and pydicom (DICOM series with shuffled file
names). What vsil reads (through the Python module, and `vsil info --json` for the placement)
must equal what the writer's own reader returns. A writer missing from the machine skips its
tests with the reason.

Run by ctest (tests/CMakeLists.txt, io.reference_writers) with PYTHONPATH=build/python and
VSIL_BINARY set."""

import json
import os
import subprocess
import zlib

import numpy as np
import pytest

import vsil

VSIL = os.environ.get("VSIL_BINARY", "vsil")
nib = pytest.importorskip("nibabel", reason="nibabel (python3-nibabel) is not installed")


def info_json(path, *args):
    result = subprocess.run([VSIL, "info", str(path), "--json", *args], capture_output=True,
                            text=True, check=True)
    return json.loads(result.stdout)


def random_affine(rng):
    """Axes permuted and flipped, then tilted by up to 15 degrees: oblique, yet with one nearest
    anatomical axis per index axis, so nibabel's and nifticlib's axis letters must agree."""
    permutation = np.eye(3)[rng.permutation(3)] * rng.choice([-1, 1], size=(3, 1))
    tilt, _ = np.linalg.qr(np.eye(3) + rng.uniform(-0.13, 0.13, size=(3, 3)))
    tilt *= np.sign(np.diag(tilt))  # a small rotation, not a flip
    affine = np.eye(4)
    affine[:3, :3] = tilt @ permutation @ np.diag(rng.uniform(0.3, 3.0, size=3))
    affine[:3, 3] = rng.uniform(-100, 100, size=3)
    return affine


NIFTI_CASES = [
    ("int16", nib.Nifti1Image, ".nii", None),
    ("uint8", nib.Nifti1Image, ".nii.gz", None),
    ("float32", nib.Nifti1Pair, ".hdr", None),
    ("float64", nib.Nifti2Image, ".nii", None),
    ("int32", nib.Nifti2Image, ".nii.gz", None),
    ("uint16", nib.Nifti1Image, ".nii.gz", (0.25, -1024.0)),
    ("int8", nib.Nifti1Pair, ".img.gz", (3.0, 0.5)),
]


@pytest.mark.parametrize("dtype,image_class,extension,scaling", NIFTI_CASES,
                         ids=[c[0] + c[2] for c in NIFTI_CASES])
def test_nifti_written_by_nibabel_reads_as_nibabel_reads_it(tmp_path, dtype, image_class,
                                                            extension, scaling):
    rng = np.random.default_rng(zlib.crc32((dtype + extension).encode()))
    shape = tuple(int(n) for n in rng.integers(2, 12, size=3))
    info = np.iinfo(dtype) if np.dtype(dtype).kind in "iu" else None
    data = (rng.integers(info.min, int(info.max) + 1, size=shape, dtype=dtype) if info
            else rng.normal(0, 100, size=shape).astype(dtype))
    affine = random_affine(rng)
    image = image_class(data, affine)
    image.set_sform(affine, code="mni")
    if scaling:
        image.header.set_slope_inter(*scaling)
    path = tmp_path / ("volume" + extension)
    nib.save(image, str(path))

    expected = np.asarray(nib.load(str(path)).get_fdata(dtype=np.float64))  # applies scaling
    volume = vsil.load(str(path))
    got = np.asarray(volume.data, dtype=np.float64).transpose(2, 1, 0)  # (z,y,x) -> (i,j,k)
    assert got.shape == shape
    np.testing.assert_array_equal(got, expected.astype(np.float32).astype(np.float64))
    np.testing.assert_allclose(volume.spacing, nib.load(str(path)).header.get_zooms()[:3],
                               rtol=1e-6)

    report = info_json(path)
    sform = [o for o in report["file"]["orientations"] if o["name"] == "sform"][0]
    np.testing.assert_allclose(np.array(sform["world_from_index"]), affine, atol=1e-4)
    assert sform["axes"] == "".join(nib.aff2axcodes(affine))
    assert report["file"]["format"].startswith("NIfTI-2" if image_class is nib.Nifti2Image
                                               else "NIfTI-1")


def test_a_nifti_crop_equals_nibabel_slicing(tmp_path):
    rng = np.random.default_rng(7)
    data = rng.integers(-3000, 3000, size=(9, 8, 7), dtype=np.int16)
    path = tmp_path / "crop.nii.gz"
    nib.save(nib.Nifti1Image(data, np.eye(4)), str(path))
    volume = vsil.load(str(path), crop="1:8,2:,0:5", stride=2)
    got = np.asarray(volume.data).transpose(2, 1, 0)
    np.testing.assert_array_equal(got, data[1:8:2, 2::2, 0:5:2])


def new_dicom_dataset(sop_class):
    """An empty CT data set of `sop_class`, its File Meta in explicit VR little endian."""
    pytest.importorskip("pydicom", reason="pydicom (python3-pydicom) is not installed")
    from pydicom.dataset import Dataset, FileMetaDataset
    from pydicom.uid import ExplicitVRLittleEndian, generate_uid
    meta = FileMetaDataset()
    meta.MediaStorageSOPClassUID = sop_class
    meta.MediaStorageSOPInstanceUID = generate_uid()
    meta.TransferSyntaxUID = ExplicitVRLittleEndian
    ds = Dataset()
    ds.file_meta = meta
    ds.is_little_endian, ds.is_implicit_VR = True, False
    ds.SOPClassUID, ds.SOPInstanceUID = meta.MediaStorageSOPClassUID, meta.MediaStorageSOPInstanceUID
    ds.Modality = "CT"
    return ds


def write_dicom_series(folder, stored, spacing, slope, intercept, orientation, rng):
    """One slice per file; names shuffled and Instance Numbers against the slice order."""
    pytest.importorskip("pydicom", reason="pydicom (python3-pydicom) is not installed")
    from pydicom.uid import generate_uid
    folder.mkdir()
    row, col = np.array(orientation[:3]), np.array(orientation[3:])
    normal = np.cross(row, col)
    series, count = generate_uid(), stored.shape[0]
    names = rng.permutation(count)
    for k in range(count):
        ds = new_dicom_dataset("1.2.840.10008.5.1.4.1.1.2")  # CT Image Storage
        ds.SeriesInstanceUID, ds.InstanceNumber = series, count - k
        ds.ImageOrientationPatient = [float(v) for v in orientation]
        ds.ImagePositionPatient = [float(v) for v in np.array([5.0, -7.0, 40.0]) + k * spacing * normal]
        ds.PixelSpacing = [0.8, 0.6]
        ds.Rows, ds.Columns = stored.shape[1], stored.shape[2]
        ds.SamplesPerPixel, ds.PhotometricInterpretation = 1, "MONOCHROME2"
        ds.BitsAllocated = ds.BitsStored = 16
        ds.HighBit, ds.PixelRepresentation = 15, 1
        ds.RescaleSlope, ds.RescaleIntercept = slope, intercept
        ds.PixelData = stored[k].astype("<i2").tobytes()
        ds.save_as(str(folder / ("slice%03d.dcm" % names[k])), write_like_original=False)


def test_a_dicom_series_written_by_pydicom_reads_in_position_order(tmp_path):
    rng = np.random.default_rng(11)
    stored = rng.integers(-2000, 3000, size=(6, 5, 7), dtype=np.int16)  # slices, rows, columns
    angle = np.radians(15)
    orientation = (1, 0, 0, 0, np.cos(angle), -np.sin(angle))
    write_dicom_series(tmp_path / "series", stored, 1.5, 2.0, -1024.0, orientation, rng)
    volume = vsil.load(str(tmp_path / "series"))
    np.testing.assert_array_equal(np.asarray(volume.data), stored * 2.0 - 1024.0)
    np.testing.assert_allclose(volume.spacing, (0.6, 0.8, 1.5), rtol=1e-9)
    report = info_json(tmp_path / "series")
    assert report["file"]["format"].startswith("DICOM series (CT, 6 slices")
    assert report["file"]["rescale"] == {"slope": 2.0, "intercept": -1024.0}
    placement = np.array(report["file"]["orientations"][0]["world_from_index"])
    np.testing.assert_allclose(placement[:3, 3], (5.0, -7.0, 40.0), atol=1e-9)


@pytest.mark.parametrize("written", ["nan\\nan", "0\\0", "0.4\\0.3"])
def test_a_slice_whose_pixel_spacing_differs_from_the_first_is_refused(tmp_path, written):
    """GDCM reads a Pixel Spacing it cannot parse, or of 0, as 1, and only the first slice's
    was checked: a later slice's odd or other spacing loaded as the first's, silently."""
    import pydicom
    rng = np.random.default_rng(3)
    stored = rng.integers(0, 100, size=(4, 5, 7), dtype=np.int16)
    write_dicom_series(tmp_path / "series", stored, 1.5, 1.0, 0.0, (1, 0, 0, 0, 1, 0), rng)
    # The third slice along the normal, whatever its shuffled name.
    files = sorted((tmp_path / "series").iterdir(),
                   key=lambda f: pydicom.dcmread(f).ImagePositionPatient[2])
    ds = pydicom.dcmread(files[2])
    ds["PixelSpacing"].value = written  # as a writer put it, not parsed by pydicom
    ds.save_as(files[2])
    with pytest.raises(ValueError) as error:
        vsil.load(str(tmp_path / "series"))
    assert f"slice '{files[2].name}' has Pixel Spacing (0028,0030) '{written}'" in str(error.value)
    assert "where the first slice has '0.8\\0.6'" in str(error.value)


def write_enhanced_ct(path, stored, spacing, orientation, order, rescale, per_frame_rescale):
    """One Enhanced CT file: frames written in `order` (not by position), positions in the
    Per-frame Functional Groups, orientation and pixel spacing shared; the rescale shared or
    repeated in every frame's groups."""
    ds = new_dicom_dataset("1.2.840.10008.5.1.4.1.1.2.1")  # Enhanced CT Image Storage
    from pydicom.dataset import Dataset
    from pydicom.sequence import Sequence
    from pydicom.uid import generate_uid
    ds.SeriesInstanceUID = generate_uid()
    ds.NumberOfFrames, ds.Rows, ds.Columns = stored.shape
    ds.SamplesPerPixel, ds.PhotometricInterpretation = 1, "MONOCHROME2"
    ds.BitsAllocated = ds.BitsStored = 16
    ds.HighBit, ds.PixelRepresentation = 15, 1

    def macro(**values):
        item = Dataset()
        for name, value in values.items():
            setattr(item, name, value)
        return Sequence([item])

    def transformation():
        return macro(RescaleSlope=rescale[0], RescaleIntercept=rescale[1], RescaleType="HU")

    shared = Dataset()
    shared.PlaneOrientationSequence = macro(ImageOrientationPatient=[float(v) for v in orientation])
    shared.PixelMeasuresSequence = macro(PixelSpacing=[0.8, 0.6], SliceThickness=spacing)
    if not per_frame_rescale:
        shared.PixelValueTransformationSequence = transformation()
    ds.SharedFunctionalGroupsSequence = Sequence([shared])
    normal = np.cross(np.array(orientation[:3]), np.array(orientation[3:]))
    frames = []
    for k in order:
        frame = Dataset()
        frame.PlanePositionSequence = macro(ImagePositionPatient=[
            float(v) for v in np.array([5.0, -7.0, 40.0]) + k * spacing * normal])
        if per_frame_rescale:
            frame.PixelValueTransformationSequence = transformation()
        frames.append(frame)
    ds.PerFrameFunctionalGroupsSequence = Sequence(frames)
    ds.PixelData = np.stack([stored[k] for k in order]).astype("<i2").tobytes()
    ds.save_as(str(path), write_like_original=False)


@pytest.mark.parametrize("per_frame_rescale", [False, True])
def test_an_enhanced_ct_file_written_by_pydicom_reads_in_position_order(tmp_path,
                                                                        per_frame_rescale):
    rng = np.random.default_rng(12)
    stored = rng.integers(-2000, 3000, size=(7, 5, 6), dtype=np.int16)  # frames, rows, columns
    angle = np.radians(20)
    orientation = (1, 0, 0, 0, np.cos(angle), -np.sin(angle))
    order = rng.permutation(stored.shape[0])
    path = tmp_path / "enhanced.dcm"
    write_enhanced_ct(path, stored, 1.25, orientation, order, (0.5, -100.0), per_frame_rescale)
    volume = vsil.load(str(path))
    np.testing.assert_array_equal(np.asarray(volume.data), stored * 0.5 - 100.0)
    np.testing.assert_allclose(volume.spacing, (0.6, 0.8, 1.25), rtol=1e-9)
    cropped = vsil.load(str(path), crop=":,:,2:6", stride=2)
    np.testing.assert_array_equal(np.asarray(cropped.data), stored[2:6:2, ::2, ::2] * 0.5 - 100.0)
    report = info_json(path)
    assert report["file"]["format"].startswith("DICOM multi-frame (CT, 7 frames")
    assert report["file"]["rescale"] == {"slope": 0.5, "intercept": -100.0}
    placement = np.array(report["file"]["orientations"][0]["world_from_index"])
    np.testing.assert_allclose(placement[:3, 3], (5.0, -7.0, 40.0), atol=1e-9)
    normal = np.cross(np.array(orientation[:3]), np.array(orientation[3:]))
    np.testing.assert_allclose(placement[:3, 2], 1.25 * normal, atol=1e-9)


def test_a_latin1_series_description_is_shown_as_its_characters(tmp_path):
    """A folder of two series names the others by their description; one written in Latin-1
    (Specific Character Set ISO_IR 100) reads as its characters, not as invalid UTF-8 bytes."""
    rng = np.random.default_rng(5)
    import pydicom
    for name, count, description in (("a", 3, "Sch\xe4del"), ("b", 2, "Kn\xf6chel")):
        write_dicom_series(tmp_path / name, rng.integers(0, 9, size=(count, 4, 4), dtype=np.int16),
                           1.0, 1.0, 0.0, (1, 0, 0, 0, 1, 0), rng)
        for path in (tmp_path / name).iterdir():
            ds = pydicom.dcmread(path)
            ds.SpecificCharacterSet = "ISO_IR 100"
            ds.SeriesDescription = description
            ds.save_as(path)
            path.rename(tmp_path / (name + path.name))
    with pytest.warns(UserWarning) as warned:
        vsil.load(str(tmp_path))
    text = " ".join(str(w.message) for w in warned)
    assert "'Sch\xe4del'" in text and "'Kn\xf6chel'" in text, text
