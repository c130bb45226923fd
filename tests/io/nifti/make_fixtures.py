#!/usr/bin/env python3
"""Writes the NIfTI fixtures beside this script with nibabel, the neuroimaging reference writer
(committed; run again only to change them), and their manifest (fixtures.txt, read by
tests/io/nifti_reader_test.cpp).

Every fixture holds 4x3x2 samples; the manifest gives what a reader must find, computed here
with numpy independently of vsil: dims, spacing, the kept type, the file's type when converted,
how many samples float32 changes, the sum, first and last of the samples as float32 keeps them
(after scl_slope/scl_inter), the format vsil names, and the sform's axes and origin."""
import os
import numpy as np
import nibabel as nib

here = os.path.dirname(os.path.abspath(__file__))
DIMS = (4, 3, 2)
COUNT = DIMS[0] * DIMS[1] * DIMS[2]
SPACING = (0.5, 1.25, 2.0)

# numpy dtype -> (kept type, file type when converted)
TYPES = {
    'uint8': ('uint8', ''), 'int8': ('int8', ''), 'uint16': ('uint16', ''),
    'int16': ('int16', ''), 'uint32': ('float32', 'uint32'), 'int32': ('float32', 'int32'),
    'uint64': ('float32', 'uint64'), 'int64': ('float32', 'int64'),
    'float32': ('float32', ''), 'float64': ('float32', 'float64'),
}


def values(dtype):
    base = np.array([(i * 37) % 251 for i in range(COUNT)], dtype=np.int64)
    if dtype == 'int8': return base - 125
    if dtype == 'uint16': return base * 251
    if dtype == 'int16': return base * 100 - 12000
    if dtype == 'int32': return np.concatenate([base[:-2] * 1000 - 100000, [16777217, -2147483648]])
    if dtype == 'uint32': return np.concatenate([base[:-2] * 1000, [16777216, 4294967295]])
    if dtype == 'int64': return np.concatenate([base[:-2] - 100, [2**63 - 1, -2**63]])
    if dtype == 'uint64':  # built from Python ints: a numpy concatenation would pass float64
        return np.array([int(v) for v in base[:-2]] + [2**53 + 1, 2**63], dtype=np.uint64)
    if dtype == 'float32': return base * 0.25 - 20.5
    if dtype == 'float64': return base * 0.1
    return base


def volume(dtype):
    """The samples in x-fastest file order, as a numpy array nibabel writes (i, j, k)."""
    flat = np.array(values(dtype), dtype=dtype)
    return flat.reshape(DIMS[::-1]).transpose(2, 1, 0)


AFFINE = np.array([[-0.5, 0, 0, 10], [0, 1.25, 0, -20], [0, 0, 2.0, 30], [0, 0, 0, 1]])  # LAS
manifest = []


def fixture(name, dtype, image_class=nib.Nifti1Image, endian='<', slope=None, inter=None,
            fmt=None):
    data = volume(dtype)
    header = image_class.header_class(endianness=endian)
    header.set_data_dtype(np.dtype(dtype).newbyteorder(endian))
    image = image_class(data, AFFINE, header)
    image.header.set_zooms(SPACING)
    image.set_sform(AFFINE, code='mni')
    image.set_qform(AFFINE, code='scanner')
    if slope is not None:
        image.header.set_slope_inter(slope, inter)
    nib.save(image, os.path.join(here, name))
    # What a reader must find: the stored values, rescaled in double, kept in float32.
    stored = values(dtype)
    if slope is not None:
        exact = [slope * float(v) + inter for v in stored]
        kept_type, file_type = 'float32', dtype
    else:
        exact = [v for v in stored]
        kept_type, file_type = TYPES[dtype]
    kept = [float(np.float32(v)) if kept_type == 'float32' else float(v) for v in exact]
    inexact = sum(1 for k, v in zip(kept, exact)
                  if (int(k) != int(v) if isinstance(v, (int, np.integer)) else k != v))
    total = 0.0
    for k in kept:
        total += k
    manifest.append('%s %d %d %d %r %r %r %s %s %d %r %r %r %s %s' % (
        name, *DIMS, *SPACING, kept_type, file_type or '-', inexact, total, kept[0], kept[-1],
        fmt, 'LAS'))


for dtype in TYPES:
    fixture(dtype + '.nii', dtype, fmt='NIfTI-1_(.nii)')
fixture('int16_gzip.nii.gz', 'int16', fmt='NIfTI-1_(.nii,_gzip)')
fixture('uint8_pair.hdr', 'uint8', image_class=nib.Nifti1Pair, fmt='NIfTI-1_(.hdr/.img)')
fixture('float32_pair_gzip.hdr.gz', 'float32', image_class=nib.Nifti1Pair,
        fmt='NIfTI-1_(.hdr/.img,_gzip)')
fixture('int16_nifti2.nii', 'int16', image_class=nib.Nifti2Image, fmt='NIfTI-2_(.nii)')
fixture('uint16_nifti2_gzip.nii.gz', 'uint16', image_class=nib.Nifti2Image,
        fmt='NIfTI-2_(.nii,_gzip)')
fixture('int16_big_endian.nii', 'int16', endian='>', fmt='NIfTI-1_(.nii)')
fixture('float64_big_endian.nii', 'float64', endian='>', fmt='NIfTI-1_(.nii)')
# CT-like: stored uint16, value = 1 * stored - 1024 (Hounsfield units).
fixture('uint16_rescaled.nii', 'uint16', slope=1.0, inter=-1024.0, fmt='NIfTI-1_(.nii)')
fixture('int16_rescaled_gzip.nii.gz', 'int16', slope=0.5, inter=3.25, fmt='NIfTI-1_(.nii,_gzip)')

with open(os.path.join(here, 'fixtures.txt'), 'w') as f:
    f.write('# file dims(3) spacing(3) kept-type file-type(- when kept as stored) inexact sum '
            'first last format(_ for spaces) sform-axes (make_fixtures.py, nibabel %s)\n'
            % nib.__version__)
    f.write('\n'.join(manifest) + '\n')
