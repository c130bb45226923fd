#!/usr/bin/env python3
"""Writes the MetaImage fixtures beside this script (committed; run again only to change them),
their manifest (fixtures.txt, read by tests/io/metaimage_reader_test.cpp) and the metaimage
fuzz target's seeds (tests/fuzz/seeds/metaimage/).

Every fixture holds 4x3x2 samples of value(i) below, as its element type stores them; the
manifest gives what a reader must find, computed here independently of vsil: dims, spacing,
the kept type, the file's type when converted, how many samples float32 changes, and the sum,
first and last of the samples as float32 keeps them."""
import os, re, struct, zlib

here = os.path.dirname(os.path.abspath(__file__))
seeds = os.path.join(here, '..', '..', 'fuzz', 'seeds', 'metaimage')
DIMS = (4, 3, 2)
COUNT = DIMS[0] * DIMS[1] * DIMS[2]

# element type -> (struct code, kept type, file type when converted)
TYPES = {
    'MET_UCHAR': ('B', 'uint8', ''), 'MET_CHAR': ('b', 'int8', ''),
    'MET_USHORT': ('H', 'uint16', ''), 'MET_SHORT': ('h', 'int16', ''),
    'MET_UINT': ('I', 'float32', 'uint32'), 'MET_INT': ('i', 'float32', 'int32'),
    'MET_ULONG': ('I', 'float32', 'uint32'), 'MET_LONG': ('i', 'float32', 'int32'),
    'MET_ULONG_LONG': ('Q', 'float32', 'uint64'), 'MET_LONG_LONG': ('q', 'float32', 'int64'),
    'MET_FLOAT': ('f', 'float32', ''), 'MET_DOUBLE': ('d', 'float32', 'float64'),
}


def values(element_type):
    code = TYPES[element_type][0]
    base = [(i * 37) % 251 for i in range(COUNT)]
    if code == 'b': return [v - 125 for v in base]
    if code == 'H': return [v * 251 for v in base]
    if code == 'h': return [v * 100 - 12000 for v in base]
    if code == 'i': return [v * 1000 - 100000 for v in base[:-2]] + [16777217, -2147483648]
    if code == 'I': return [v * 1000 for v in base[:-2]] + [16777216, 4294967295]
    if code == 'q': return [v - 100 for v in base[:-2]] + [9223372036854775807, -9223372036854775808]
    if code == 'Q': return [v for v in base[:-2]] + [(1 << 53) + 1, 1 << 63]
    if code == 'f': return [v * 0.25 - 20.5 for v in base]
    if code == 'd': return [v * 0.1 for v in base]
    return base


def as_float32(v):
    return struct.unpack('<f', struct.pack('<f', float(v)))[0]


def kept(element_type, v):
    """The value vsil keeps, and whether it differs from the file's."""
    if TYPES[element_type][1] != 'float32':
        return float(v), False
    f = as_float32(v)
    if isinstance(v, int):
        return f, int(f) != v
    return f, f != v


def encode(element_type, msb):
    code = TYPES[element_type][0]
    return struct.pack(('>' if msb else '<') + str(COUNT) + code, *values(element_type))


def header(element_type, data_file, extra='', spacing='ElementSpacing = 0.5 1.25 2\n'):
    return ('ObjectType = Image\nNDims = 3\nDimSize = 4 3 2\n' + spacing + extra +
            'ElementType = ' + element_type + '\nElementDataFile = ' + data_file + '\n')


manifest = []
seed_list = []


def fixture(name, element_type, files, spacing=(0.5, 1.25, 2)):
    """files: {file name: bytes}; `name` is the one to load."""
    for file_name, data in files.items():
        with open(os.path.join(here, file_name), 'wb') as f:
            f.write(data if isinstance(data, bytes) else data.encode())
    kept_values = [kept(element_type, v) for v in values(element_type)]
    total = sum(k for k, _ in kept_values)
    inexact = sum(1 for _, changed in kept_values if changed)
    _, kept_type, file_type = TYPES[element_type]
    manifest.append('%s %d %d %d %r %r %r %s %s %d %r %r %r' % (
        name, *DIMS, *spacing, kept_type, file_type or '-', inexact, total,
        kept_values[0][0], kept_values[-1][0]))
    # A fuzz seed: the header file, and after a NUL the data file's bytes (fuzz_metaimage.cpp).
    head = files[name]
    head = head if isinstance(head, bytes) else head.encode()
    data = [d for n, d in files.items() if n != name]
    if data:  # the target writes the data file as "data"
        head = re.sub(rb'ElementDataFile = .*\n', b'ElementDataFile = data\n', head)
    seed_list.append((name, head + (b'\0' + data[0] if data else b'')))


# Every element type, detached raw (.mhd + .raw).
for element_type in TYPES:
    stem = element_type[4:].lower()
    fixture(stem + '.mhd', element_type,
            {stem + '.mhd': header(element_type, stem + '.raw', 'BinaryData = True\n'
                                   'BinaryDataByteOrderMSB = False\n'),
             stem + '.raw': encode(element_type, False)})

# zlib (.mhd + .zraw) with CompressedDataSize.
packed = zlib.compress(encode('MET_SHORT', False), 9)
fixture('short_zlib.mhd', 'MET_SHORT',
        {'short_zlib.mhd': header('MET_SHORT', 'short_zlib.zraw',
                                  'BinaryData = True\nCompressedData = True\n'
                                  'CompressedDataSize = %d\n' % len(packed)),
         'short_zlib.zraw': packed})
# zlib without CompressedDataSize, attached, 64-bit integers (two samples rounded).
fixture('ulong_long_zlib.mha', 'MET_ULONG_LONG',
        {'ulong_long_zlib.mha': header('MET_ULONG_LONG', 'LOCAL', 'CompressedData = True\n').encode() +
         zlib.compress(encode('MET_ULONG_LONG', False))})
# Attached (.mha), ElementSize instead of ElementSpacing.
fixture('float_local.mha', 'MET_FLOAT',
        {'float_local.mha': header('MET_FLOAT', 'LOCAL', 'BinaryData = True\n',
                                   spacing='ElementSize = 0.5 1.25 2\n').encode() +
         encode('MET_FLOAT', False)})
# Big-endian (ElementByteOrderMSB, the older spelling).
fixture('ushort_msb.mha', 'MET_USHORT',
        {'ushort_msb.mha': header('MET_USHORT', 'LOCAL', 'ElementByteOrderMSB = True\n').encode() +
         encode('MET_USHORT', True)})
fixture('int_msb.mha', 'MET_INT',
        {'int_msb.mha': header('MET_INT', 'LOCAL', 'BinaryDataByteOrderMSB = True\n').encode() +
         encode('MET_INT', True)})
# HeaderSize: 16 bytes skipped in the data file; -1: the data are the file's last bytes.
fixture('int_headersize.mhd', 'MET_INT',
        {'int_headersize.mhd': header('MET_INT', 'int_headersize.raw', 'HeaderSize = 16\n'),
         'int_headersize.raw': b'sixteen bytes!!\n' + encode('MET_INT', False)})
fixture('double_tail.mhd', 'MET_DOUBLE',
        {'double_tail.mhd': header('MET_DOUBLE', 'double_tail.raw', 'HeaderSize = -1\n'),
         'double_tail.raw': b'a header of some other format\n' + encode('MET_DOUBLE', False)})
# ASCII samples (BinaryData = False).
fixture('char_ascii.mha', 'MET_CHAR',
        {'char_ascii.mha': header('MET_CHAR', 'LOCAL', 'BinaryData = False\n') +
         ' '.join(str(v) for v in values('MET_CHAR')) + '\n'})

with open(os.path.join(here, 'fixtures.txt'), 'w') as f:
    f.write('# file dims(3) spacing(3) kept-type file-type(- when kept as stored) inexact sum '
            'first last (make_fixtures.py)\n')
    f.write('\n'.join(manifest) + '\n')

os.makedirs(seeds, exist_ok=True)
for name, data in seed_list:
    with open(os.path.join(seeds, name.replace('.', '_') + '.bin'), 'wb') as f:
        f.write(data)
