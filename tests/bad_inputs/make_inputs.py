#!/usr/bin/env python3
"""Writes the bad-input corpus beside this script (committed; run again only to change it).
Each file is small; cases.json says which command reads it and the exact error it must get."""
import base64, gzip, lzma, os, struct, zlib

here = os.path.dirname(os.path.abspath(__file__))


def write(name, data):
    with open(os.path.join(here, name), 'wb') as f:
        f.write(data if isinstance(data, bytes) else data.encode())


nrrd = 'NRRD0004\ntype: %s\ndimension: 3\nsizes: %s\n%sencoding: %s\n\n'
write('truncated.nrrd', (nrrd % ('uint8', '4 4 4', '', 'raw')).encode() + bytes(10))
write('oversized_dims.nrrd', (nrrd % ('uint8', '100000 100000 100000', '', 'raw')).encode() + bytes(8))
write('huge_number.nrrd', (nrrd % ('uint8', '4 4 99999999999999999999999', '', 'raw')).encode() + bytes(8))
write('nan_floats.nrrd', (nrrd % ('float', '2 2 2', 'endian: little\n', 'raw')).encode() +
      struct.pack('<8f', 0, 1, 2, float('nan'), 4, 5, 6, 7))
write('double_beyond_float32.nrrd', (nrrd % ('double', '2 1 1', 'endian: little\n', 'raw')).encode() +
      struct.pack('<2d', 1e300, 0))
write('wrong_magic.nrrd', (nrrd % ('uint8', '2 2 2', '', 'raw')).replace('NRRD0004', 'NRRX0004').encode() + bytes(8))
# 1 MiB of zeros in ~1 KiB of gzip, for a 64-byte volume: must stop after 65 bytes of output.
# A multi-file NRRD (its file names on the lines after "data file: LIST") and a version past 5.
write('nrrd_list.nhdr', 'NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 2\nencoding: raw\n'
      'data file: LIST\ns0.raw\ns1.raw\n')
write('nrrd_version9.nrrd', (nrrd % ('uint8', '4 4 4', '', 'raw')).replace('NRRD0004', 'NRRD0009').encode() + bytes(64))
write('gzip_bomb.nrrd', (nrrd % ('uint8', '4 4 4', '', 'gzip')).encode() + gzip.compress(bytes(1 << 20), 9, mtime=0))
write('empty.nrrd', b'')
write('gzip_trailing_junk.nrrd', (nrrd % ('uint8', '4 4 4', '', 'gzip')).encode() + gzip.compress(bytes(64), 9, mtime=0) + b'JUNKJUNK')
# A header claiming 1024³ uint16 samples with 16 bytes of payload, and one whose data file does
# not exist: the texture and memory checks answer first (they run before any payload is opened
# or read); with a small enough --crop they pass and the payload's own error follows.
write('claims_1024_cube.nrrd', (nrrd % ('uint16', '1024 1024 1024', 'endian: little\n', 'raw')).encode() + bytes(16))
write('missing_data.nhdr', (nrrd % ('uint16', '1024 1024 1024', 'endian: little\n', 'raw')).replace('encoding: raw\n', 'encoding: raw\ndata file: no_such_data.raw\n'))
write('unknown_format.xyz', b'some bytes\n')

vti_head = ('<VTKFile type="ImageData" byte_order="LittleEndian" header_type="UInt32"%s>\n'
            '<ImageData WholeExtent="0 1 0 1 0 1" Spacing="1 1 1"><Piece><PointData>\n')
vti_tail = '</PointData></Piece></ImageData>\n'
write('malformed.vti', vti_head % '' + '<DataArray type="UInt8" format="ascii">1 2 3 4 5 6 7 8\n</PointData></Piece>\n')
packed = zlib.compress(bytes(1 << 20), 9)
block = struct.pack('<4I', 1, 8, 0, len(packed)) + packed
write('zlib_bomb.vti', (vti_head % ' compressor="vtkZLibDataCompressor"' +
                        '<DataArray type="UInt8" format="appended" offset="0"/>\n' + vti_tail +
                        '<AppendedData encoding="raw">_').encode() + block + b'</AppendedData></VTKFile>\n')
# LZ4 and LZMA (xz) blocks get zlib's bomb check: a hand-made LZ4 block whose one match repeats
# a zero byte ~25000 times, and 1 MiB of zeros in xz, each promised as 8 bytes.
lz4_bomb = bytes([0x1f, 0x00, 0x01, 0x00]) + bytes([255] * 100) + bytes([0, 0x50]) + bytes(5)
xz_bomb = lzma.compress(bytes(1 << 20), format=lzma.FORMAT_XZ)
for name, compressor, packed in (('lz4_bomb.vti', 'vtkLZ4DataCompressor', lz4_bomb),
                                 ('lzma_bomb.vti', 'vtkLZMADataCompressor', xz_bomb)):
    block = struct.pack('<4I', 1, 8, 0, len(packed)) + packed
    write(name, (vti_head % (' compressor="%s"' % compressor) +
                 '<DataArray type="UInt8" format="appended" offset="0"/>\n' + vti_tail +
                 '<AppendedData encoding="raw">_').encode() + block + b'</AppendedData></VTKFile>\n')
write('bad_base64.vti', vti_head % '' + '<DataArray type="UInt8" format="binary">CAAAAA**AQIDBAUGBw==</DataArray>\n' + vti_tail + '</VTKFile>\n')

vtk = '# vtk DataFile Version 3.0\nbad\n%s\nDATASET STRUCTURED_POINTS\nDIMENSIONS %s\nPOINT_DATA %s\nSCALARS s %s\nLOOKUP_TABLE default\n'
write('huge_numbers.vtk', vtk % ('ASCII', '99999999999999999999 1 1', '1', 'float') + '1\n')
write('truncated.vtk', (vtk % ('BINARY', '4 4 4', '64', 'unsigned_char')).encode() + bytes(20))
write('inf_floats.vtk', vtk % ('ASCII', '2 1 1', '2', 'float') + '1 inf\n')

os.makedirs(os.path.join(here, 'directory.vti'), exist_ok=True)
write('directory.vti/README', 'A directory named like a volume: vsil must say it is a directory.\n')
write('small.raw', bytes(100))

# Transfer functions (--tf) and illustration styles (--style), the illustrate technique.
write('tf_empty.json', '[]\n')
write('tf_not_json.json', '[{"value": 0, "color": "red", "opacity": 0.5}\n')
write('tf_nonmonotonic.json', '[{"value": 10, "color": "red", "opacity": 0.5},\n'
                              ' {"value": 5, "color": "blue", "opacity": 1}]\n')
write('tf_bad_opacity.json', '[{"value": 0, "color": "red", "opacity": 1.5}]\n')
write('tf_duplicate_key.json', '[{"value": 0, "color": "red", "opacity": 0.5, "opacity": 1}]\n')
write('style_unknown_key.json', '{"effects": ["tone"], "shininess": 3}\n')
write('style_bad_effect.json', '{"effects": ["tone", "glow"]}\n')
write('style_none_and_tone.json', '{"effects": ["none", "tone"]}\n')
write('style_empty_tf.json', '{"transfer_function": ""}\n')
write('style_tf_folder.json', '{"transfer_function": "."}\n')
write('tf_preset_format.json', '{"description": "a copy of a preset", "units": "hu", "points": '
      '[{"value": 0, "color": "#000000", "opacity": 0}, {"value": 100, "color": "#ffffff", '
      '"opacity": 1}]}\n')
write('style_bad_parameter.json', '{"parameters": {"k_gc": "high"}}\n')
# Headers that misdescribe their axes or payload (round 6): a colour axis and a kinds count
# unlike the dimension, units that differ between axes, more text values than the sizes give,
# and MetaImage's two byte-order fields disagreeing.
write('nrrd_kinds_rgb.nrrd', (nrrd % ('uint8', '3 4 4', 'kinds: RGB-color domain domain\n', 'raw')).encode() + bytes(48))
write('nrrd_kinds_two.nrrd', (nrrd % ('uint8', '2 2 2', 'kinds: domain domain\n', 'raw')).encode() + bytes(8))
write('nrrd_mixed_units.nrrd', (nrrd % ('uint8', '2 2 2', 'space dimension: 3\nspace units: "mm" "km" "mm"\n', 'raw')).encode() + bytes(8))
write('nrrd_two_units.nrrd', (nrrd % ('uint8', '2 2 2', 'space dimension: 3\nspace units: "mm" "mm"\n', 'raw')).encode() + bytes(8))
write('nrrd_ascii_extra.nrrd', (nrrd % ('uint8', '2 2 2', '', 'ascii')) + ' '.join(['7'] * 9) + '\n')
write('mha_ascii_extra.mha', 'ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\n'
      'BinaryData = False\nElementDataFile = LOCAL\n' + ' '.join(['7'] * 9) + '\n')
write('vtk_ascii_extra.vtk', vtk % ('ASCII', '2 2 2', '8', 'unsigned_char') + ' '.join(['7'] * 9) + '\n')
write('vti_ascii_extra.vti', vti_head % '' + '<DataArray type="UInt8" Name="s" format="ascii">' +
      ' '.join(['7'] * 9) + '</DataArray>\n' + vti_tail + '</VTKFile>\n')
write('mha_byte_orders_disagree.mha', b'ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\n'
      b'ElementType = MET_USHORT\nElementByteOrderMSB = False\nBinaryDataByteOrderMSB = True\n'
      b'ElementDataFile = LOCAL\n' + bytes(16))
# Colours with an alpha where nothing reads it (a sample's, a sketch line's, a point's).
write('style_color_alpha.json', '{"color": "#ff000080"}\n')
write('tf_color_alpha.json', '[{"value": 0, "color": "transparent", "opacity": 0},\n'
                             ' {"value": 1, "color": "white", "opacity": 1}]\n')

# Rule bases (technique semantic): a malformed shape, sphere files missing or not images.
write('rules_bad_shape.rules', 'attribute density from data {\n  high = trapezoid(0.2, 0.5, 1)\n}\n')
write('rules_spike_shape.rules', 'attribute density from data {\n  spike = triangle(0.5, 0.5, 0.5)\n}\n')
rules = ('attribute density from data { high = trapezoid(0.2, 0.5, 1, 1) }\n'
         'style bone { spheres = "%s"  opaque = trapezoid(0.6, 0.9, 1, 1) }\n'
         'rule if density is high then bone is opaque\n')
write('rules_missing_spheres.rules', rules % 'missing_spheres.png')
write('rules_bad_spheres.rules', rules % 'not_an_image.png')
write('not_an_image.png', 'this is not a PNG\n')

# Sphere maps (demip --sphere-map FILE.png): an empty file, a PNG whose header declares an image
# 0 pixels wide, and one whose header declares 100000x50000 pixels and holds nothing more (it
# must be refused from the header, before anything is decoded or allocated).
def png_chunk(kind, data):
    return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data))


def png_header(width, height):
    return b'\x89PNG\r\n\x1a\n' + png_chunk(b'IHDR', struct.pack('>IIBBBBB', width, height, 8, 2, 0, 0, 0))


write('empty_map.png', b'')
write('zero_width_map.png', png_header(0, 16) + png_chunk(b'IEND', b''))
write('huge_map.png', png_header(100000, 50000))

# A whole 16x8 RGB PNG, then cut inside its image data, and one with a byte of the image data
# changed (its chunk's CRC no longer matches): refused from the chunk walk, before libpng would
# print a line of its own.
rows = b''.join(b'\x00' + b''.join(bytes((x * 16, y * 32, 128)) for x in range(16)) for y in range(8))
whole = png_header(16, 8) + png_chunk(b'IDAT', zlib.compress(rows, 9)) + png_chunk(b'IEND', b'')
write('truncated_map.png', whole[:60])
corrupt = bytearray(whole)
corrupt[45] ^= 0xff  # inside the IDAT chunk's data
write('corrupt_map.png', bytes(corrupt))

# MetaImage (.mha attached, .mhd detached): truncated data, a DimSize larger than the data file,
# a zlib bomb, a CompressedDataSize past the end, several channels, a 2D image, a missing data
# file, a list of slice files.
mha = 'ObjectType = Image\nNDims = %s\nDimSize = %s\n%sElementType = MET_UCHAR\nElementDataFile = %s\n'
write('truncated.mha', (mha % (3, '4 4 4', '', 'LOCAL')).encode() + bytes(10))
write('lying_dimsize.mhd', mha % (3, '8 8 8', '', 'lying_dimsize.raw'))
write('lying_dimsize.raw', bytes(64))
write('zlib_bomb.mha', (mha % (3, '4 4 4', 'CompressedData = True\n', 'LOCAL')).encode() +
      zlib.compress(bytes(1 << 20), 9))
write('zlib_trailing_junk.mha', (mha % (3, '4 4 4', 'CompressedData = True\n', 'LOCAL')).encode() +
      zlib.compress(bytes(64), 9) + b'JUNKJUNK')
write('bad_compressed_size.mha', (mha % (3, '4 4 4', 'CompressedData = True\nCompressedDataSize = 999999\n',
                                         'LOCAL')).encode() + zlib.compress(bytes(64), 9))
write('multichannel.mha', (mha % (3, '2 2 2', 'ElementNumberOfChannels = 3\n', 'LOCAL')).encode() + bytes(24))
write('image_2d.mha', (mha % (2, '4 4', '', 'LOCAL')).encode() + bytes(16))
write('missing_data.mhd', mha % (3, '4 4 4', '', 'no_such_data.raw'))
write('slice_list.mhd', mha % (3, '4 4 4', '', 'LIST'))

# NIfTI-1 (.nii, .nii.gz, .hdr/.img): truncated data, a 4D series, complex samples, a negative
# size, a vox_offset far past any header, a cut gzip stream, a pair without its .img, text named
# .nii, sizes past the memory limit.
def nifti1(dims=(4, 4, 4), datatype=2, bitpix=8, vox_offset=352.0, extra_dims=(), magic=b'n+1\0',
           slope=0.0, inter=0.0):
    header = bytearray(348)
    struct.pack_into('<i', header, 0, 348)
    dim = [3 + len(extra_dims)] + list(dims) + list(extra_dims)
    struct.pack_into('<8h', header, 40, *(dim + [1] * (8 - len(dim))))
    struct.pack_into('<hh', header, 70, datatype, bitpix)
    struct.pack_into('<8f', header, 76, 1, 1, 1, 1, 0, 0, 0, 0)
    struct.pack_into('<f', header, 108, vox_offset)
    struct.pack_into('<ff', header, 112, slope, inter)
    header[344:348] = magic
    return bytes(header) + (bytes(4) if magic == b'n+1\0' else b'')


write('nifti_truncated.nii', nifti1() + bytes(10))
write('nifti_4d.nii', nifti1(extra_dims=(5,)) + bytes(320))
write('nifti_complex.nii', nifti1(datatype=32, bitpix=64) + bytes(512))
write('nifti_negative_dim.nii', nifti1(dims=(4, -4, 4)) + bytes(64))
write('nifti_vox_offset.nii', nifti1(vox_offset=1e12) + bytes(64))
noise = bytes((i * 7919 + (i >> 3) * 104729) % 251 for i in range(16 * 16 * 8))
whole = gzip.compress(nifti1(dims=(16, 16, 8)) + noise, 9, mtime=0)
write('nifti_cut.nii.gz', whole[:len(whole) * 3 // 4])
# The same stream with its CRC flipped, and without its 8-byte trailer (length and CRC): the
# samples all inflate, the stream's check fails.
bad_crc = bytearray(whole)
bad_crc[-8] ^= 1
write('nifti_bad_crc.nii.gz', bytes(bad_crc))
write('nifti_no_trailer.nii.gz', whole[:-8])
write('nifti_pair_no_img.hdr', nifti1(vox_offset=0.0, magic=b'ni1\0'))
write('nifti_text.nii', 'this is not a NIfTI file, only text named like one\n' * 10)
write('nifti_oversized.nii', nifti1(dims=(30000, 30000, 30000)) + bytes(64))


# A CT data set with its File Meta Information, explicit VR little endian framing.
def ct_dataset(sop_class, instance_uid, syntax):
    from pydicom.dataset import Dataset, FileMetaDataset
    meta = FileMetaDataset()
    meta.MediaStorageSOPClassUID, meta.MediaStorageSOPInstanceUID = sop_class, instance_uid
    meta.TransferSyntaxUID = syntax
    ds = Dataset()
    ds.file_meta = meta
    ds.is_little_endian, ds.is_implicit_VR = True, False
    ds.SOPClassUID, ds.SOPInstanceUID, ds.Modality = sop_class, instance_uid, 'CT'
    return ds


# DICOM series (folders; written with pydicom): a missing slice, a slice cut short, no DICOM at
# all, slices of two sizes, a header promising 65535 x 65535 slices, colour (RGB) pixels.
def dicom_series(folder, count=3, positions=None, rows=3, columns=4, pixels=None, rgb=False,
                 orientation=(1.0, 0.0, 0.0, 0.0, 1.0, 0.0), pixel_spacing=None, slope=None):
    from pydicom.uid import ExplicitVRLittleEndian, generate_uid
    path = os.path.join(here, folder)
    os.makedirs(path, exist_ok=True)
    series = generate_uid(entropy_srcs=['bad', folder])
    for k in range(count):
        ds = ct_dataset('1.2.840.10008.5.1.4.1.1.2',
                        generate_uid(entropy_srcs=['bad', folder, str(k)]), ExplicitVRLittleEndian)
        ds.SeriesInstanceUID, ds.InstanceNumber = series, k + 1
        ds.ImageOrientationPatient = list(orientation)
        ds.ImagePositionPatient = [0.0, 0.0, float(positions[k] if positions else 2 * k)]
        if pixel_spacing is None:
            ds.PixelSpacing = [1.0, 1.0]
        else:  # written as text, as a hostile file would hold it (pydicom checks DS values)
            ds.add_new(0x00280030, 'DS', None)
            ds[0x00280030]._value = pixel_spacing
        if slope is not None:
            ds.add_new(0x00281052, 'DS', None)
            ds[0x00281052]._value = '0'
            ds.add_new(0x00281053, 'DS', None)
            ds[0x00281053]._value = slope
        r, c = (rows[k], columns[k]) if isinstance(rows, list) else (rows, columns)
        ds.Rows, ds.Columns = r, c
        ds.SamplesPerPixel = 3 if rgb else 1
        ds.PhotometricInterpretation = 'RGB' if rgb else 'MONOCHROME2'
        if rgb:
            ds.PlanarConfiguration = 0
        ds.BitsAllocated = ds.BitsStored = 8 if rgb else 16
        ds.HighBit, ds.PixelRepresentation = (7 if rgb else 15), 0
        ds.PixelData = pixels if pixels is not None else bytes((3 if rgb else 2) * r * c)
        ds.save_as(os.path.join(path, 'slice%d.dcm' % k), write_like_original=False)


dicom_series('dicom_missing_slice', count=4, positions=[0, 2, 4, 8])
dicom_series('dicom_truncated')
with open(os.path.join(here, 'dicom_truncated', 'slice1.dcm'), 'r+b') as f:
    f.truncate(os.path.getsize(f.name) - 10)
os.makedirs(os.path.join(here, 'dicom_none'), exist_ok=True)
write('dicom_none/readme.txt', 'no DICOM here\n')
dicom_series('dicom_mixed_sizes', rows=[3, 3, 5], columns=[4, 4, 4])
dicom_series('dicom_huge', rows=65535, columns=65535, pixels=bytes(8))
dicom_series('dicom_rgb', rgb=True)
dicom_series('dicom_no_normal', orientation=(1.0, 0.0, 0.0, 1.0, 0.0, 0.0))
# Multi-frame (enhanced CT) files: frames without positions (no Per-frame Functional Groups),
# frames with different rescales, a frame missing between the others.
def dicom_multiframe(folder, frames=3, positions=None, slopes=None, per_frame=True):
    from pydicom.dataset import Dataset
    from pydicom.sequence import Sequence
    from pydicom.uid import ExplicitVRLittleEndian, generate_uid
    path = os.path.join(here, folder)
    os.makedirs(path, exist_ok=True)
    ds = ct_dataset('1.2.840.10008.5.1.4.1.1.2.1',  # Enhanced CT Image Storage
                    generate_uid(entropy_srcs=['bad', folder]), ExplicitVRLittleEndian)
    ds.SeriesInstanceUID = generate_uid(entropy_srcs=['bad series', folder])
    ds.NumberOfFrames, ds.Rows, ds.Columns = frames, 3, 4
    ds.SamplesPerPixel, ds.PhotometricInterpretation = 1, 'MONOCHROME2'
    ds.BitsAllocated = ds.BitsStored = 16
    ds.HighBit, ds.PixelRepresentation = 15, 0
    shared = Dataset()
    orientation = Dataset()
    orientation.ImageOrientationPatient = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0]
    shared.PlaneOrientationSequence = Sequence([orientation])
    ds.SharedFunctionalGroupsSequence = Sequence([shared])
    if per_frame:
        items = []
        for k in range(frames):
            item, position = Dataset(), Dataset()
            position.ImagePositionPatient = [0.0, 0.0, float(positions[k] if positions else 2 * k)]
            item.PlanePositionSequence = Sequence([position])
            if slopes:
                transformation = Dataset()
                transformation.RescaleSlope, transformation.RescaleIntercept = slopes[k], 0.0
                item.PixelValueTransformationSequence = Sequence([transformation])
            items.append(item)
        ds.PerFrameFunctionalGroupsSequence = Sequence(items)
    ds.PixelData = bytes(2 * 3 * 4 * frames)
    ds.save_as(os.path.join(path, 'frames.dcm'), write_like_original=False)


dicom_multiframe('dicom_frames_no_positions', per_frame=False)
dicom_multiframe('dicom_frames_rescales', slopes=[1.0, 2.0, 1.0])
dicom_multiframe('dicom_frames_missing', frames=4, positions=[0, 2, 4, 8])
# Found by libFuzzer (target dicom): a multi-frame file whose Pixel Data (7fe0,0010) declares
# about 4 GB and holds 72 bytes. GDCM's read of the header up to the pixel data read them too,
# so the DICOM reader's process allocated the declared 4 GB before the file was refused.
dicom_multiframe('dicom_frames_cut_short')
with open(os.path.join(here, 'dicom_frames_cut_short', 'frames.dcm'), 'r+b') as f:
    data = f.read()
    at = data.rindex(b'\xe0\x7f\x10\x00OW\x00\x00')
    f.seek(at + 8)
    f.write(struct.pack('<I', 0xf90000f0))
# Found by libFuzzer (target dicom): a slice of tests/io/dicom's ct_series with three bytes
# changed trips an assert() inside GDCM's File Meta Information reader, which aborts.
slice_bytes = bytearray(open(os.path.join(here, '..', 'io', 'dicom', 'ct_series', 'IM0000'), 'rb').read())
for offset, value in ((166, 0x30), (679, 0x08), (870, 0x27)):
    slice_bytes[offset] = value
os.makedirs(os.path.join(here, 'dicom_gdcm_assert'), exist_ok=True)
write('dicom_gdcm_assert/slice.dcm', bytes(slice_bytes))


# One 8 x 8 16-bit CT slice in RLE Lossless whose RLE header (64 bytes: the segment count, 15
# offsets) declares `segments`, each segment (2 where none are declared) a literal run of
# `segment_bytes` zeros. Every element fits the file: GDCM reads the header and fails only
# decoding the pixels.
def dicom_rle_slice(folder, segments, segment_bytes):
    from pydicom.encaps import encapsulate
    from pydicom.uid import RLELossless, generate_uid
    ds = ct_dataset('1.2.840.10008.5.1.4.1.1.2', generate_uid(entropy_srcs=['bad', folder, '0']),
                    RLELossless)
    ds.SeriesInstanceUID = generate_uid(entropy_srcs=['bad', folder])
    ds.ImageOrientationPatient, ds.ImagePositionPatient = [1, 0, 0, 0, 1, 0], [0, 0, 0]
    ds.PixelSpacing, ds.Rows, ds.Columns = [1, 1], 8, 8
    ds.SamplesPerPixel, ds.PhotometricInterpretation = 1, 'MONOCHROME2'
    ds.BitsAllocated, ds.BitsStored, ds.HighBit, ds.PixelRepresentation = 16, 16, 15, 1
    segment = bytes([segment_bytes - 1]) + bytes(segment_bytes)
    offsets = [64 + k * len(segment) for k in range(max(segments, 1))]
    fragment = struct.pack('<16I', segments, *offsets, *[0] * (15 - len(offsets)))
    fragment += segment * max(segments, 2)
    ds.PixelData = encapsulate([fragment + bytes(len(fragment) % 2)])
    ds['PixelData'].VR = 'OB'
    os.makedirs(os.path.join(here, folder), exist_ok=True)
    ds.save_as(os.path.join(here, folder, 'slice.dcm'), write_like_original=False)


# 3 segments where 16-bit grey needs 2: GDCM's RLECodec::Decode decodes 3 x (128 / 3) = 126
# bytes of the 128 and fails its assert(check == len) (an abort).
dicom_rle_slice('dicom_rle_segments', 3, 42)
# 0 segments: RLEFrame::Read checks the first offset only for 1 or more, and DecodeByStreams
# divides the frame's length by the count (SIGFPE).
dicom_rle_slice('dicom_rle_no_segments', 0, 64)
# Issue 33. JSON nested 100000 deep (200 KB): refused while parsed, before any walk of the value
# could overflow the stack.
write('tf_deep.json', '[' * 100000 + ']' * 100000)
write('style_deep.json', '{"effects": ' + '[' * 100000 + ']' * 100000 + '}')
# A spacing whose axes differ 10^7 times: slices one step of the finest axis apart would number
# 5.7e7 per frame (it was an out-of-memory kill after minutes).
write('tiny_spacing.mha', (mha % (3, '4 4 4', 'ElementSpacing = 1 1 1e-7\n', 'LOCAL')).encode() + bytes(64))
# 1 KiB of gzip whose NIfTI header declares 2048³ samples: refused from the compressed size.
write('nifti_gz_claims_2048.nii.gz', gzip.compress(nifti1(dims=(2048, 2048, 2048)) + bytes(512), 9, mtime=0))
# A spacing whose slice gap is 10^-7 of its pixel spacing (DICOM positions 1e-7 apart).
dicom_series('dicom_tiny_gap', positions=[0, 1e-7, 2e-7])
# A slice whose Pixel Data holds 10 bytes of the 24 its 3 x 4 16-bit pixels need (the file is
# whole: GDCM read it as zeros).
dicom_series('dicom_short_pixels', pixels=bytes(10))
# Pixel Spacing and Rescale Slope GDCM cannot parse, or 0: it read them as 1 (or no rescale).
dicom_series('dicom_spacing_nan', pixel_spacing='nan\\1')
dicom_series('dicom_spacing_zero', pixel_spacing='0\\1')
dicom_series('dicom_spacing_text', pixel_spacing='abc\\1')
dicom_series('dicom_slope_nan', slope='nan')
# NIfTI slopes that are not numbers (nifticlib reads them as 0, no scaling) and a bad magic.
write('nifti_slope_nan.nii', nifti1(slope=float('nan')) + bytes(64))
write('nifti_slope_inf.nii', nifti1(slope=float('inf')) + bytes(64))
write('nifti_bad_magic.nii', nifti1(magic=b'xyz\0') + bytes(4 + 64))
# A rule base whose sphere strip declares 100000 x 100000 pixels (OpenCV's assertion, before),
# and PNGs whose IHDR holds 4 bytes.
write('rules_huge_spheres.rules', rules % 'huge_spheres.png')
write('huge_spheres.png', png_header(100000, 100000))
write('short_ihdr_map.png', b'\x89PNG\r\n\x1a\n' + png_chunk(b'IHDR', struct.pack('>I', 64)) + png_chunk(b'IEND', b''))
# A NRRD whose sizes hold 2^32.
write('sizes_2_32.nrrd', (nrrd % ('uint8', '4 4 4294967296', '', 'raw')).encode() + bytes(8))
# Valid chunks (every CRC right) around a corrupt deflate stream: only libpng sees it; its own
# "libpng error" line must not reach stderr.
packed = bytearray(zlib.compress(rows, 9))
packed[len(packed) // 2] ^= 0x55
write('bad_deflate_map.png', png_header(16, 8) + png_chunk(b'IDAT', bytes(packed)) + png_chunk(b'IEND', b''))
