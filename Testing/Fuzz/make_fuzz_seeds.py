#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Writes the seed inputs of the fuzz targets into Testing/Fuzz/seeds/TARGET/.

Seeds are small cuts of real files (Data/, Data/proteins/awkward/, Testing/Data/), with the
option byte each target reads first. The XTC and TRR cuts come from write_trajectory_seeds
(GROMACS' own writers): pass its output folder. scripts/fuzz.sh reads these seeds; a long run's
corpus, minimised with -merge=1, may be added to them.

    Testing/Fuzz/make_fuzz_seeds.py TRAJECTORY_SEEDS_DIR
"""
import base64
import pathlib
import struct
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
SEEDS = ROOT / "Testing" / "Fuzz" / "seeds"
ATOM_RECORDS = 60


# Records and categories the reader interprets; the rest of a header is left out of seeds.
PDB_SKIPPED = ("REMARK", "SEQRES", "JRNL", "AUTHOR", "REVDAT", "SOURCE", "KEYWDS", "COMPND",
               "DBREF", "SEQADV", "FORMUL", "HETNAM", "HETSYN", "SITE", "HET ")
CIF_KEPT = ("data_", "_entry.", "_struct.", "_cell.", "_symmetry.", "_struct_conf.",
            "_struct_sheet_range.", "_struct_conn.", "_atom_site.")


def cut_pdb(text):
    """The first ATOM_RECORDS atom records of a PDB file, with the records before them that
    the reader interprets."""
    lines, atoms = [], 0
    for line in text.splitlines():
        if line.startswith(("ATOM", "HETATM")):
            atoms += 1
            if atoms > ATOM_RECORDS:
                break
        if not line.startswith(PDB_SKIPPED):
            lines.append(line)
    return "\n".join(lines + ["END"]) + "\n"


def cif_blocks(text):
    """The '#'-separated blocks of a PDB mmCIF file that hold categories the reader reads."""
    blocks, block = [], []
    for line in text.splitlines():
        if line.startswith("#"):
            blocks.append(block)
            block = []
        else:
            block.append(line)
    blocks.append(block)
    kept = [b for b in blocks if any(line.startswith(CIF_KEPT) for line in b)]
    return "\n#\n".join("\n".join(b) for b in kept)


def cut_cif(text):
    """The mmCIF file's interpreted categories, up to ATOM_RECORDS rows of its _atom_site
    loop."""
    lines, in_atoms, rows = [], False, 0
    for line in cif_blocks(text).splitlines():
        if line.startswith("_atom_site."):
            in_atoms = True
        elif in_atoms and not line.startswith("_"):
            if line.startswith(("#", "loop_")):
                break
            rows += 1
            if rows > ATOM_RECORDS:
                break
        lines.append(line)
    return "\n".join(lines) + "\n"


def cut_gro(text, atoms=40):
    """The first `atoms` atoms of a .gro file's first frame, with its box."""
    lines = text.splitlines()
    count = int(lines[1])
    body = lines[2:2 + min(atoms, count)]
    box = lines[2 + count]
    return "\n".join([lines[0], "%5d" % len(body)] + body + [box]) + "\n"


def read_off(text):
    """Points and triangles of a small OFF file."""
    words = text.split()
    vertices, faces = int(words[1]), int(words[2])
    numbers = words[4:]
    points = [tuple(float(v) for v in numbers[3 * i:3 * i + 3]) for i in range(vertices)]
    rest, triangles = numbers[3 * vertices:], []
    for _ in range(faces):
        count = int(rest[0])
        triangles.append(tuple(int(v) for v in rest[1:1 + count]))
        rest = rest[1 + count:]
    return points, triangles


def obj_text(points, triangles):
    lines = ["v %g %g %g" % p for p in points]
    lines += ["f " + " ".join(str(i + 1) for i in t) for t in triangles]
    return "\n".join(lines) + "\n"


def cut_obj(text, vertices=40):
    """The first `vertices` vertices of an OBJ file and the faces that use only them."""
    lines, seen = [], 0
    for line in text.splitlines():
        if line.startswith("v "):
            seen += 1
            if seen <= vertices:
                lines.append(line)
        elif line.startswith("f "):
            corners = [int(c.split("/")[0]) for c in line.split()[1:]]
            if max(corners) <= vertices:
                lines.append(" ".join(["f"] + [str(c) for c in corners]))
        elif not line.startswith(("vn", "vt")):
            lines.append(line)
    return "\n".join(lines) + "\n"


def stl_ascii(points, triangles):
    lines = ["solid seed"]
    for t in triangles:
        lines += ["facet normal 0 0 0", "outer loop"]
        lines += ["vertex %g %g %g" % points[i] for i in t[:3]]
        lines += ["endloop", "endfacet"]
    return "\n".join(lines + ["endsolid seed"]) + "\n"


def stl_binary(points, triangles):
    data = b"seed".ljust(80, b" ") + struct.pack("<I", len(triangles))
    for t in triangles:
        data += struct.pack("<3f", 0, 0, 0)
        for i in t[:3]:
            data += struct.pack("<3f", *points[i])
        data += b"\0\0"
    return data


def vtp(points, triangles, binary):
    """A VTK XML PolyData file, ascii or with base64 binary data inline."""
    def array(kind, name, components, values):
        attributes = 'type="%s" Name="%s" NumberOfComponents="%d"' % (kind, name, components)
        if binary:
            code = {"Float32": "f", "Int64": "q"}[kind]
            raw = struct.pack("<%d%s" % (len(values), code), *values)
            payload = base64.b64encode(struct.pack("<Q", len(raw)) + raw).decode()
            return '<DataArray %s format="binary">%s</DataArray>' % (attributes, payload)
        return '<DataArray %s format="ascii">%s</DataArray>' % (
            attributes, " ".join(str(v) for v in values))
    coordinates = [c for p in points for c in p]
    connectivity = [i for t in triangles for i in t]
    offsets = [sum(len(t) for t in triangles[:k + 1]) for k in range(len(triangles))]
    header = 'header_type="UInt64" ' if binary else ""
    return ('<?xml version="1.0"?>\n<VTKFile type="PolyData" version="1.0" '
            'byte_order="LittleEndian" %s>\n<PolyData>\n'
            '<Piece NumberOfPoints="%d" NumberOfPolys="%d">\n<Points>%s</Points>\n'
            '<Polys>%s%s</Polys>\n</Piece>\n</PolyData>\n</VTKFile>\n') % (
        header, len(points), len(triangles), array("Float32", "Points", 3, coordinates),
        array("Int64", "connectivity", 1, connectivity), array("Int64", "offsets", 1, offsets))


def ply_ascii(points, triangles):
    lines = ["ply", "format ascii 1.0", "element vertex %d" % len(points), "property float x",
             "property float y", "property float z", "element face %d" % len(triangles),
             "property list uchar int vertex_indices", "end_header"]
    lines += ["%g %g %g" % p for p in points]
    lines += ["%d " % len(t) + " ".join(str(i) for i in t) for t in triangles]
    return "\n".join(lines) + "\n"


def biomt(serial, rows, shifted=False):
    """The three REMARK 350 BIOMT lines of one operator; `shifted`: the serial pushes the numbers
    one column right, as 1m4x.pdb writes serials past 999."""
    serial_field = ("%6d" if shifted else "%4d") % serial
    return ["REMARK 350   BIOMT%d%s%10.6f%10.6f%10.6f     %10.5f" % ((i + 1, serial_field) + row)
            for i, row in enumerate(rows)]


def assembly_seeds(proteins):
    """A PDB file with REMARK 350 (chain lists continued by AND CHAINS, two generators, a shifted
    serial) and an mmCIF file with assembly categories (ranges, an id that is no number, a
    product of lists), both over crambin's first atoms."""
    identity = ((1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0))
    turn = ((0, -1, 0, 10.5), (1, 0, 0, -3.25), (0, 0, 1, 0))
    remarks = ["REMARK 350 BIOMOLECULE: 1",
               "REMARK 350 AUTHOR DETERMINED BIOLOGICAL UNIT: DIMERIC",
               "REMARK 350 APPLY THE FOLLOWING TO CHAINS: A, B,",
               "REMARK 350                    AND CHAINS: C"]
    remarks += biomt(1, identity) + biomt(1000, turn, shifted=True)
    remarks += ["REMARK 350 BIOMOLECULE: 2", "REMARK 350 APPLY THE FOLLOWING TO CHAINS: A"]
    remarks += biomt(1, turn) + ["REMARK 350 APPLY THE FOLLOWING TO CHAINS: B"] + biomt(2, identity)
    pdb = cut_pdb((proteins / "1crn.pdb").read_text("latin-1"))
    write("fuzz_structure", "assembly_biomt.pdb", 0, "\n".join(remarks) + "\n" + pdb)
    operators = ["loop_", "_pdbx_struct_oper_list.id", "_pdbx_struct_oper_list.type"]
    for i in range(1, 4):
        operators += ["_pdbx_struct_oper_list.matrix[%d][%d]" % (i, j) for j in range(1, 4)]
        operators.append("_pdbx_struct_oper_list.vector[%d]" % i)
    for name, rows in (("1", identity), ("2", turn), ("3", turn), ("P", turn)):
        operators.append(name + " 'point symmetry operation' " +
                         " ".join("%g" % v for row in rows for v in row))
    assemblies = ["loop_", "_pdbx_struct_assembly.id", "_pdbx_struct_assembly.details",
                  "_pdbx_struct_assembly.method_details", "_pdbx_struct_assembly.oligomeric_details",
                  "_pdbx_struct_assembly.oligomeric_count",
                  "1 'complete point assembly' ? ? ?", "2 author_defined_assembly ? ? ?",
                  "#", "loop_", "_pdbx_struct_assembly_gen.assembly_id",
                  "_pdbx_struct_assembly_gen.oper_expression",
                  "_pdbx_struct_assembly_gen.asym_id_list",
                  "1 '(1-3)(P,1)' A", "2 '1,2' A", "2 (3) A"]
    cif = cut_cif((proteins / "1crn.cif").read_text("latin-1"))
    write("fuzz_structure", "assembly_product.cif", 1,
          cif + "#\n" + "\n".join(operators + ["#"] + assemblies) + "\n#\n")


def write(target, name, option, payload):
    folder = SEEDS / target
    folder.mkdir(parents=True, exist_ok=True)
    if isinstance(payload, str):
        payload = payload.encode("latin-1")
    (folder / name).write_bytes(bytes([option]) + payload)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    trajectories = pathlib.Path(sys.argv[1])
    proteins = ROOT / "Data" / "proteins"
    awkward = proteins / "awkward"

    # Structures: every awkward file as it is, the small real ones cut, in each file form.
    structures = []
    for path in sorted(awkward.glob("*.pdb")) + sorted(awkward.glob("*.cif")):
        if path.stat().st_size <= 16384:
            structures.append((path, path.read_text("latin-1")))
    for path in sorted(proteins.glob("*.pdb")):
        structures.append((path, cut_pdb(path.read_text("latin-1"))))
    for path in sorted(proteins.glob("*.cif")):
        structures.append((path, cut_cif(path.read_text("latin-1"))))
    for index, (path, text) in enumerate(structures):
        is_cif = path.suffix == ".cif"
        write("fuzz_structure", path.stem + path.suffix, 1 if is_cif else 0, text)
        # Some seeds in the other forms: no extension, gzipped, and with options set.
        if index % 3 == 0:
            write("fuzz_structure", path.stem + "_bare" + path.suffix, 2, text)
        if index % 3 == 1:
            write("fuzz_structure", path.stem + "_gz" + path.suffix, 0x83 if is_cif else 3, text)
        if index % 3 == 2:
            options = (1 if is_cif else 0) | (4 << (index // 3 % 5))
            write("fuzz_structure", path.stem + "_options" + path.suffix, options, text)
    assembly_seeds(proteins)

    # GRO: the awkward files as they are, the membranes cut; then as trajectories too.
    for path in sorted(awkward.glob("*.gro")):
        write("fuzz_gro", path.name, 0, path.read_text("latin-1"))
    for path in sorted((ROOT / "Data" / "membranes").glob("*.gro")):
        write("fuzz_gro", path.name, 0, cut_gro(path.read_text("latin-1")))
        write("fuzz_gro", path.stem + "_beads.gro", 2, cut_gro(path.read_text("latin-1"), 12))

    # Meshes, one extension per option byte (byte % 5: obj, ply, stl, off, vtp).
    for path in sorted((ROOT / "Data" / "meshes" / "bad").glob("*.off")):
        text = path.read_text("latin-1")
        write("fuzz_mesh", path.name, 3, text)
        points, triangles = read_off(text)
        write("fuzz_mesh", path.stem + ".obj", 0, obj_text(points, triangles))
        write("fuzz_mesh", path.stem + "_ascii.stl", 2, stl_ascii(points, triangles))
        write("fuzz_mesh", path.stem + "_binary.stl", 2, stl_binary(points, triangles))
        write("fuzz_mesh", path.stem + "_ascii.vtp", 4, vtp(points, triangles, False))
        write("fuzz_mesh", path.stem + "_binary.vtp", 4, vtp(points, triangles, True))
        write("fuzz_mesh", path.stem + "_ascii.ply", 1, ply_ascii(points, triangles))
    obj = (ROOT / "Data" / "meshes" / "hipsc_cell_membrane_1.obj").read_text("latin-1")
    write("fuzz_mesh", "hipsc_cut.obj", 0, cut_obj(obj))
    for path in sorted((ROOT / "Testing" / "Data" / "meshes").glob("*.ply")):
        if path.stat().st_size <= 8192:
            write("fuzz_mesh", path.name, 1, path.read_bytes())

    # XTC and TRR.
    for path in sorted(trajectories.glob("*.xtc")) + sorted(trajectories.glob("*.trr")):
        trr = path.suffix == ".trr"
        write("fuzz_trajectory", path.name, int(trr), path.read_bytes())
        write("fuzz_trajectory", path.stem + "_skip" + path.suffix, int(trr) | 2, path.read_bytes())


if __name__ == "__main__":
    main()
