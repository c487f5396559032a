# SPDX-License-Identifier: BSD-2-Clause
"""A small reader of Mach-O libraries (the macOS binaries of the FMUs, which no Mac runs here):
the slices of a universal (fat) file, and per slice its CPU, file type, the libraries it
loads, its install name, its minimum macOS (LC_BUILD_VERSION) and its code signature, whose
page hashes are checked against the slice's bytes as macOS checks them. Layouts from Apple's
<mach-o/loader.h>, <mach-o/fat.h> and the code-signing blob formats (xnu's cs_blobs.h)."""
import hashlib
import struct
from dataclasses import dataclass, field

FAT_MAGIC = 0xCAFEBABE
MH_MAGIC_64 = 0xFEEDFACF
CPU = {0x01000007: "x86_64", 0x0100000C: "arm64"}
MH_DYLIB = 6
LC_LOAD_DYLIBS = {0xC, 0x80000018, 0x8000001F, 0x20, 0x80000023}   # load, weak, re-export, lazy, upward
LC_ID_DYLIB = 0xD
LC_CODE_SIGNATURE = 0x1D
LC_BUILD_VERSION = 0x32
LC_VERSION_MIN_MACOSX = 0x24
PLATFORM_MACOS = 1
CSMAGIC_EMBEDDED_SIGNATURE = 0xFADE0CC0
CSMAGIC_CODEDIRECTORY = 0xFADE0C02
CS_HASHTYPE = {1: hashlib.sha1, 2: hashlib.sha256}


@dataclass
class Slice:
    arch: str
    filetype: int
    dylibs: list = field(default_factory=list)
    install_name: str = None
    platform: int = None
    minos: tuple = None
    signature: dict = None


def slices(data):
    """(arch, bytes) of each slice: the fat file's, or the one of a thin file."""
    magic, = struct.unpack_from(">I", data)
    if magic == FAT_MAGIC:
        count, = struct.unpack_from(">I", data, 4)
        out = []
        for i in range(count):
            cputype, _, offset, size, _ = struct.unpack_from(">iIIII", data, 8 + 20 * i)
            out.append((CPU.get(cputype & 0xFFFFFFFF, hex(cputype)), data[offset:offset + size]))
        return out
    return [(parse(data).arch, data)]


def version(v):
    return (v >> 16, (v >> 8) & 0xFF, v & 0xFF)


def c_string(data, start):
    return data[start:data.index(b"\0", start)].decode()


def code_signature(data, offset, size):
    """The embedded signature's CodeDirectory, and whether every page hash matches the slice."""
    blob = data[offset:offset + size]
    magic, _, count = struct.unpack_from(">III", blob)
    if magic != CSMAGIC_EMBEDDED_SIGNATURE:
        return {"magic": magic}
    for i in range(count):
        _, at = struct.unpack_from(">II", blob, 12 + 8 * i)
        if struct.unpack_from(">I", blob, at)[0] != CSMAGIC_CODEDIRECTORY:
            continue
        (_, _, cd_version, flags, hash_offset, ident_offset, _, n_code, code_limit, hash_size, hash_type, _,
         page_log2) = struct.unpack_from(">IIIIIIIIIBBBB", blob, at)
        page = 1 << page_log2
        algorithm = CS_HASHTYPE[hash_type]
        pages_ok = n_code == -(-code_limit // page) and all(
            blob[at + hash_offset + k * hash_size:at + hash_offset + (k + 1) * hash_size]
            == algorithm(data[k * page:min((k + 1) * page, code_limit)]).digest()
            for k in range(n_code))
        return {"magic": magic, "flags": flags, "identifier": c_string(blob, at + ident_offset),
                "code_limit": code_limit, "pages": n_code, "pages_ok": pages_ok, "covers_offset": offset}
    return {"magic": magic, "code_directory": None}


def parse(data):
    """One thin 64-bit slice."""
    magic, cputype, _, filetype, ncmds, _, _, _ = struct.unpack_from("<IiIIIIII", data)
    if magic != MH_MAGIC_64:
        raise ValueError(f"not a 64-bit Mach-O slice (magic {magic:#x})")
    s = Slice(CPU.get(cputype & 0xFFFFFFFF, hex(cputype)), filetype)
    at = 32
    for _ in range(ncmds):
        cmd, size = struct.unpack_from("<II", data, at)
        if cmd in LC_LOAD_DYLIBS:
            s.dylibs.append(c_string(data, at + struct.unpack_from("<I", data, at + 8)[0]))
        elif cmd == LC_ID_DYLIB:
            s.install_name = c_string(data, at + struct.unpack_from("<I", data, at + 8)[0])
        elif cmd == LC_BUILD_VERSION:
            s.platform, minos = struct.unpack_from("<II", data, at + 8)
            s.minos = version(minos)
        elif cmd == LC_VERSION_MIN_MACOSX:
            s.platform, s.minos = PLATFORM_MACOS, version(struct.unpack_from("<I", data, at + 8)[0])
        elif cmd == LC_CODE_SIGNATURE:
            offset, length = struct.unpack_from("<II", data, at + 8)
            s.signature = code_signature(data, offset, length)
        at += size
    return s
