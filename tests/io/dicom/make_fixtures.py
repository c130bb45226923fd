#!/usr/bin/env python3
"""Writes the DICOM fixtures beside this script with pydicom (and GDCM's gdcmconv for JPEG 2000
and JPEG-LS; committed, run again only to change them) and their manifest (fixtures.txt, read by
tests/io/dicom_reader_test.cpp).

Each series folder holds axial-ish CT slices of 4 columns x 3 rows. File names are shuffled and
Instance Numbers run against the slice order: a reader must sort by Image Position (Patient)
along the slice normal. The manifest gives, computed here with numpy independently of vsil: the
folder, dims, spacing, the sum, first and last sample in slice order after Rescale Slope and
Intercept, the slice normal's axis letters and the first slice's position."""
import os, shutil, subprocess
import numpy as np
import pydicom
from pydicom.dataset import Dataset, FileMetaDataset
from pydicom.uid import ExplicitVRLittleEndian, RLELossless, generate_uid

here = os.path.dirname(os.path.abspath(__file__))
ROWS, COLS = 3, 4
PIXEL_SPACING = (0.7, 0.5)  # DICOM order: between rows (y), between columns (x)
manifest = []


def slice_values(k, n):
    base = np.array([((i + 1) * 37 + k * 101) % 997 for i in range(ROWS * COLS)], dtype=np.int64)
    return (base * 3 + k).reshape(ROWS, COLS)


def write_series(folder, count, spacing=2.5, positions=None, orientation=(1, 0, 0, 0, 1, 0),
                 slope=1.0, intercept=-1024.0, series_uid=None, dtype=np.uint16, start=0,
                 description='CT series'):
    """Writes `count` slices; returns (uid, stored volume in slice order, positions)."""
    path = os.path.join(here, folder)
    os.makedirs(path, exist_ok=True)
    row, col = np.array(orientation[:3], float), np.array(orientation[3:], float)
    normal = np.cross(row, col)
    origin = np.array([-12.0, 30.5, 100.0])
    if positions is None:
        positions = [k * spacing for k in range(count)]
    uid = series_uid or generate_uid(entropy_srcs=[folder, description])
    study = generate_uid(entropy_srcs=['study'])
    stored = []
    order = list(range(count))
    rng = np.random.default_rng(len(folder) * 7 + count)
    names = ['IM%04d' % v for v in rng.permutation(count) + start]
    for k in order:
        values = slice_values(k + start, count).astype(dtype)
        stored.append(values)
        meta = FileMetaDataset()
        meta.MediaStorageSOPClassUID = '1.2.840.10008.5.1.4.1.1.2'
        meta.MediaStorageSOPInstanceUID = generate_uid(entropy_srcs=[folder, description, str(k)])
        meta.TransferSyntaxUID = ExplicitVRLittleEndian
        ds = Dataset()
        ds.file_meta = meta
        ds.is_little_endian, ds.is_implicit_VR = True, False
        ds.SOPClassUID = meta.MediaStorageSOPClassUID
        ds.SOPInstanceUID = meta.MediaStorageSOPInstanceUID
        ds.Modality = 'CT'
        ds.PatientName = 'Fixture^Volume'
        ds.StudyInstanceUID = study
        ds.SeriesInstanceUID = uid
        ds.SeriesDescription = description
        ds.InstanceNumber = count - k  # against the slice order
        ds.ImageOrientationPatient = [float(v) for v in orientation]
        ds.ImagePositionPatient = [float(v) for v in origin + positions[k] * normal]
        ds.PixelSpacing = list(PIXEL_SPACING)
        ds.SliceThickness = spacing
        ds.Rows, ds.Columns = ROWS, COLS
        ds.SamplesPerPixel = 1
        ds.PhotometricInterpretation = 'MONOCHROME2'
        ds.BitsAllocated = ds.BitsStored = 16
        ds.HighBit = 15
        ds.PixelRepresentation = 1 if np.dtype(dtype).kind == 'i' else 0
        ds.RescaleSlope, ds.RescaleIntercept = slope, intercept
        ds.PixelData = values.tobytes()
        ds.save_as(os.path.join(path, names[k]), write_like_original=False)
    return uid, stored, positions, normal, origin


def record(folder, stored, spacing, slope, intercept, axes, first_position):
    volume = np.stack(stored)  # z, y, x: x fastest in file order
    kept = [float(np.float32(slope * float(v) + intercept)) for v in volume.ravel()]
    total = 0.0
    for v in kept:
        total += v
    manifest.append('%s %d %d %d %r %r %r %r %r %r %s %r %r %r' % (
        folder, COLS, ROWS, len(stored), PIXEL_SPACING[1], PIXEL_SPACING[0], spacing, total,
        kept[0], kept[-1], axes, *first_position))


for folder in ('ct_series', 'ct_oblique', 'ct_rle', 'ct_jpeg', 'ct_jpegls', 'two_series',
               'missing_slice', 'no_dicom'):
    shutil.rmtree(os.path.join(here, folder), ignore_errors=True)

uid, stored, _, _, origin = write_series('ct_series', 5)
record('ct_series', stored, 2.5, 1.0, -1024.0, 'LPS', origin)
# Tilted: rows along x, columns along y and down z; the normal runs between +z and +y.
c, s = np.cos(np.radians(20)), np.sin(np.radians(20))
_, stored, _, normal, origin = write_series('ct_oblique', 4, spacing=1.25,
                                            orientation=(1, 0, 0, 0, c, -s), slope=0.5,
                                            intercept=-100.0, dtype=np.int16)
record('ct_oblique', stored, 1.25, 0.5, -100.0, 'LPS', origin)
# Compressed transfer syntaxes: RLE by pydicom, lossless JPEG and JPEG-LS by gdcmconv (its
# JPEG 2000 encoder crashes on images this small).
_, stored, _, _, origin = write_series('ct_rle', 5)
for name in os.listdir(os.path.join(here, 'ct_rle')):
    file = os.path.join(here, 'ct_rle', name)
    ds = pydicom.dcmread(file)
    ds.compress(RLELossless)
    ds.save_as(file)
record('ct_rle', stored, 2.5, 1.0, -1024.0, 'LPS', origin)
for folder, flag in (('ct_jpeg', '--jpeg'), ('ct_jpegls', '--jpegls')):
    _, stored, _, _, origin = write_series(folder, 5)
    for name in os.listdir(os.path.join(here, folder)):
        file = os.path.join(here, folder, name)
        subprocess.run(['gdcmconv', flag, file, file + '.tmp'], check=True)
        os.replace(file + '.tmp', file)
    record(folder, stored, 2.5, 1.0, -1024.0, 'LPS', origin)
# Two series in one folder: the larger (6 slices) is read, the other named in a warning.
_, stored, _, _, origin = write_series('two_series', 6, description='CT big')
record('two_series', stored, 2.5, 1.0, -1024.0, 'LPS', origin)
small_uid, stored, _, _, origin = write_series('two_series', 3, spacing=3.0, start=6,
                                               description='CT small')
record('two_series:' + small_uid, stored, 3.0, 1.0, -1024.0, 'LPS', origin)
# A slice missing (positions 0, 2.5, 5, 10, 12.5): refused, not stretched.
write_series('missing_slice', 5, positions=[0, 2.5, 5, 10, 12.5])
os.makedirs(os.path.join(here, 'no_dicom'))
with open(os.path.join(here, 'no_dicom', 'notes.txt'), 'w') as f:
    f.write('a file that is not DICOM, in a folder that has none\n')

with open(os.path.join(here, 'fixtures.txt'), 'w') as f:
    f.write('# folder[:series] dims(3) spacing(3) sum first last axes first-position(3) '
            '(make_fixtures.py, pydicom %s)\n' % pydicom.__version__)
    f.write('\n'.join(manifest) + '\n')
