#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Writes ParaView's server-manager XML for MesoLens' readers, filters and representation from their
class headers.

One source of truth: a property's name, type and documentation come from the class header
(its ``///@{ ... ///@}`` block and the vtkSet/vtkGet macros in it, with the Core field a
comment names as "see mesolens::X::field" appended), and its default, range and enumeration from
the built class itself (its getters after construction, the clamp macros' GetXMinValue and
GetXMaxValue, its SetXToY methods). The spec (ParaView/MesoLens/proxies.json) adds only what no
header says: menus, labels, file types, inputs and which string properties name arrays. The
representation's own properties are its mapper's (same names, documentation and defaults); those
it shares with ParaView's Surface representation (colouring, material, transform) are fixed here.

Usage: paraview_proxies.py SPEC SOURCE_DIR OUTPUT.xml  (with the built `mesolens` importable)
"""
import json
import os
import re
import sys
from xml.sax.saxutils import escape, quoteattr

SET_MACRO = re.compile(
    r"vtkSet(?P<kind>Clamp|Vector3|Vector2|String|StdStringFromChar)?Macro\(\s*(?P<name>\w+)"
    r"(?:\s*,\s*(?P<type>[\w ]+?))?\s*(?:,[^)]*)?\)")
SET_TO = re.compile(r"void\s+Set(\w+?)To(\w+)\(\)")
CORE_REFERENCE = re.compile(r"see (mesolens::(\w+)::(\w+))")


def header_blocks(path):
    """The ///@{ ... ///@} blocks of a header: (documentation, block text)."""
    text = open(path, encoding="utf-8").read()
    blocks = []
    for match in re.finditer(r"///@\{(.*?)///@\}", text, re.S):
        body = match.group(1)
        doc = " ".join(line.strip()[3:].strip() for line in body.splitlines()
                       if line.strip().startswith("///"))
        blocks.append((doc, body))
    return blocks


def class_brief(path):
    """The @brief and the first paragraph after it of a class header."""
    text = open(path, encoding="utf-8").read()
    match = re.search(r"@brief\s+(.*?)\n \*\n(.*?)(?:\n \*\n|\*/)", text, re.S)
    if not match:
        return "", ""
    clean = lambda s: " ".join(part.strip(" *") for part in s.splitlines()).strip()
    return clean(match.group(1)), clean(match.group(2))


class CoreDocs:
    """The documentation of Core's parameter struct fields, by (struct, field)."""

    def __init__(self, include_dir):
        self.fields = {}
        for root, _, files in os.walk(include_dir):
            for name in files:
                if name.endswith(".h"):
                    self._read(os.path.join(root, name))

    def _read(self, path):
        text = open(path, encoding="utf-8").read()
        for struct in re.finditer(r"struct (\w+)\s*\{(.*?)\n\};", text, re.S):
            comment = []
            for line in struct.group(2).splitlines():
                stripped = line.strip()
                if stripped.startswith("///") and not stripped.startswith("///<"):
                    comment.append(stripped[3:].strip())
                    continue
                field = re.match(r"[\w:<>, ]+?\s+(\w+)(?:\s*=\s*[^;]+|\{[^;]*\})?;\s*(?:///<\s*(.*))?", stripped)
                if field:
                    doc = " ".join(comment + ([field.group(2)] if field.group(2) else []))
                    self.fields[(struct.group(1), field.group(1))] = doc
                comment = []

    def explain(self, doc):
        """`doc` with the Core fields it refers to ("see mesolens::X::field") explained."""
        notes = []
        for full, struct, field in CORE_REFERENCE.findall(doc):
            if (struct, field) in self.fields:
                notes.append(f"{full}: {self.fields[(struct, field)]}")
        return doc if not notes else doc + " " + " ".join(notes)


def properties_of(header, skip):
    """(name, kind, type, documentation, enumeration names) of each settable property."""
    found = []
    for doc, body in header_blocks(header):
        enums = {}
        for prop, entry in SET_TO.findall(body):
            enums.setdefault(prop, []).append(entry)
        for macro in SET_MACRO.finditer(body):
            name = macro.group("name")
            if name in skip:
                continue
            kind = macro.group("kind") or ""
            value_type = (macro.group("type") or "").strip()
            if kind in ("String", "StdStringFromChar"):
                value_type = "string"
            found.append((name, kind, value_type, doc, enums.get(name, [])))
    return found


def xml_property(instance, name, kind, value_type, doc, enum_names, hints, core):
    """The XML of one property, its default read from `instance`."""
    getter = getattr(instance, "Get" + name)
    value = getter()
    documentation = f"<Documentation>{escape(core.explain(doc))}</Documentation>"
    attributes = f'name="{name}" command="Set{name}"'
    if name in hints.get("advanced", []):
        attributes += ' panel_visibility="advanced"'
    if value_type == "string":
        array = hints.get("arrays", {}).get(name)
        if array:
            # The arrays of the input to choose from; NoDefault keeps "" (none) until one is.
            return (f'<StringVectorProperty {attributes} number_of_elements="1" default_values="">'
                    f'<ArrayListDomain name="array_list" input_domain_name="{array}_arrays">'
                    f'<RequiredProperties><Property name="Input" function="Input"/>'
                    f"</RequiredProperties></ArrayListDomain>"
                    f"<Hints><NoDefault/></Hints>{documentation}</StringVectorProperty>")
        files = '<FileListDomain name="files"/>' if name in hints.get("files", []) else ""
        return (f'<StringVectorProperty {attributes} number_of_elements="1" '
                f'default_values={quoteattr(value or "")}>{files}{documentation}'
                "</StringVectorProperty>")
    count = 3 if kind == "Vector3" else 2 if kind == "Vector2" else 1
    values = list(value) if count > 1 else [value]
    if value_type == "bool":
        text = " ".join(str(int(bool(v))) for v in values)
        return (f'<IntVectorProperty {attributes} number_of_elements="{count}" '
                f'default_values="{text}"><BooleanDomain name="bool"/>{documentation}'
                f"</IntVectorProperty>")
    integer = value_type == "int"
    tag = "IntVectorProperty" if integer else "DoubleVectorProperty"
    text = " ".join(repr(int(v)) if integer else repr(float(v)) for v in values)
    domain = ""
    if enum_names:
        entries = []
        for entry in enum_names:
            probe = type(instance)()
            getattr(probe, f"Set{name}To{entry}")()
            entries.append(f'<Entry value="{getattr(probe, "Get" + name)()}" '
                           f'text="{re.sub(r"(?<!^)(?=[A-Z])", " ", entry)}"/>')
        domain = '<EnumerationDomain name="enum">' + "".join(entries) + "</EnumerationDomain>"
    elif kind == "Clamp":
        low = getattr(instance, f"Get{name}MinValue")()
        high = getattr(instance, f"Get{name}MaxValue")()
        range_tag = "IntRangeDomain" if integer else "DoubleRangeDomain"
        domain = f'<{range_tag} name="range" min="{low}" max="{high}"/>'
    return (f'<{tag} {attributes} number_of_elements="{count}" default_values="{text}">'
            f"{domain}{documentation}</{tag}>")


def proxy_xml(spec, source_dir, core, mesolens):
    """The XML of one reader or filter proxy."""
    class_name = spec["class"]
    header = None
    for module in ("Filters", "Rendering"):
        candidate = os.path.join(source_dir, module, class_name + ".h")
        if os.path.exists(candidate):
            header = candidate
    if header is None:
        raise SystemExit(f"no header for {class_name}")
    instance = getattr(mesolens, class_name)()
    skip = set(spec.get("skip", []))
    brief, details = class_brief(header)
    parts = [f'<SourceProxy name="{spec["name"]}" class="{class_name}" label={quoteattr(spec["label"])}>',
             f"<Documentation short_help={quoteattr(brief)} long_help={quoteattr(brief)}>"
             f"{escape(details)}</Documentation>"]
    reader = spec.get("reader")
    if reader:
        parts.append(f'<StringVectorProperty name="FileName" command="{reader["command"]}" '
                     'animateable="0" number_of_elements="1" panel_visibility="never">'
                     '<FileListDomain name="files"/>'
                     f'<Documentation>The file to read.</Documentation></StringVectorProperty>')
        skip.add(reader["command"][3:])
    for port in spec.get("inputs", []):
        types = "".join(f'<DataType value="{t}"/>' for t in port.get("types", ["vtkPolyData"]))
        arrays = "".join(f'<InputArrayDomain name="{kind}_arrays" attribute_type="{kind}" optional="1"/>'
                         for kind in sorted(set(spec.get("arrays", {}).values())))
        optional = "<Hints><Optional/></Hints>" if port.get("optional") else ""
        parts.append(f'<InputProperty name="{port["name"]}" port_index="{port.get("port", 0)}" '
                     f'command="SetInputConnection"><ProxyGroupDomain name="groups">'
                     f'<Group name="sources"/><Group name="filters"/></ProxyGroupDomain>'
                     f'<DataTypeDomain name="input_type">{types}</DataTypeDomain>{arrays}{optional}'
                     f"<Documentation>{escape(port.get('help', ''))}</Documentation></InputProperty>")
    headers = [header]
    base = spec.get("base_header")
    if base:
        headers.insert(0, os.path.join(source_dir, base))
    for path in headers:
        for name, kind, value_type, doc, enums in properties_of(path, skip):
            parts.append(xml_property(instance, name, kind, value_type, doc, enums, spec, core))
    for name, choices in spec.get("implicit_functions", {}).items():
        doc = next((d for path in headers for d, body in header_blocks(path)
                    if f"Set{name}(" in body), "")
        entries = "".join(f'<Proxy group="implicit_functions" name="{c}"/>' for c in choices)
        parts.append(f'<ProxyProperty name="{name}" command="Set{name}">'
                     f'<ProxyListDomain name="proxy_list">{entries}</ProxyListDomain>'
                     f"<Documentation>{escape(core.explain(doc))}</Documentation></ProxyProperty>")
    for name, label in spec.get("point_widgets", {}).items():
        # A handle in the render view that sets the point: drag it to move the lens.
        parts.append(f'<PropertyGroup label={quoteattr(label)} panel_widget="InteractiveHandle">'
                     f'<Property function="WorldPosition" name="{name}"/></PropertyGroup>')
    if spec.get("time"):
        parts.append('<DoubleVectorProperty name="TimestepValues" repeatable="1" '
                     'information_only="1"><TimeStepsInformationHelper/>'
                     "<Documentation>The times the file holds.</Documentation>"
                     "</DoubleVectorProperty>")
    hints = []
    if reader:
        hints.append(f'<ReaderFactory extensions="{" ".join(reader["extensions"])}" '
                     f'file_description={quoteattr(reader["description"])}/>')
    if spec.get("category"):
        hints.append(f'<ShowInMenu category={quoteattr(spec["category"])}/>')
    if hints:
        parts.append("<Hints>" + "".join(hints) + "</Hints>")
    parts.append("</SourceProxy>")
    return "\n".join(parts)


# Properties of the representation that ParaView's Surface representation also has: linked to it,
# so colouring, material and transform carry over when the user switches representation.
SURFACE_PROPERTIES = """
<InputProperty name="Input" command="SetInputConnection">
  <DataTypeDomain name="input_type" composite_data_supported="1"><DataType value="vtkDataSet"/></DataTypeDomain>
  <InputArrayDomain name="input_array_any" attribute_type="point" optional="1"/>
</InputProperty>
<IntVectorProperty name="Visibility" command="SetVisibility" number_of_elements="1" default_values="1">
  <BooleanDomain name="bool"/>
</IntVectorProperty>
<StringVectorProperty name="ColorArrayName" command="SetInputArrayToProcess" element_types="0 0 0 0 2"
    number_of_elements="5">
  <RepresentedArrayListDomain name="array_list" input_domain_name="input_array_any">
    <RequiredProperties><Property function="Input" name="Input"/></RequiredProperties>
  </RepresentedArrayListDomain>
  <Documentation>The point array to colour the atoms by; none: element colours.</Documentation>
</StringVectorProperty>
<ProxyProperty name="LookupTable" command="SetLookupTable">
  <ProxyGroupDomain name="groups"><Group name="lookup_tables"/></ProxyGroupDomain>
  <Documentation>The colour map for the colour array.</Documentation>
</ProxyProperty>
<DoubleVectorProperty name="SpecularPower" command="SetSpecularPower" number_of_elements="1"
    default_values="100">
  <DoubleRangeDomain name="range" min="0" max="100"/>
</DoubleVectorProperty>
<DoubleVectorProperty name="AmbientColor" command="SetAmbientColor" number_of_elements="3"
    default_values="1 1 1"><DoubleRangeDomain name="range" min="0 0 0" max="1 1 1"/>
</DoubleVectorProperty>
<DoubleVectorProperty name="DiffuseColor" command="SetDiffuseColor" number_of_elements="3"
    default_values="1 1 1"><DoubleRangeDomain name="range" min="0 0 0" max="1 1 1"/>
  <Documentation>Multiplies the element colours (white: as they are).</Documentation>
</DoubleVectorProperty>
<DoubleVectorProperty name="SpecularColor" command="SetSpecularColor" number_of_elements="3"
    default_values="1 1 1"><DoubleRangeDomain name="range" min="0 0 0" max="1 1 1"/>
</DoubleVectorProperty>
<IntVectorProperty name="Pickable" command="SetPickable" number_of_elements="1" default_values="1">
  <BooleanDomain name="bool"/>
</IntVectorProperty>
<DoubleVectorProperty name="Position" command="SetPosition" number_of_elements="3" default_values="0 0 0"/>
<DoubleVectorProperty name="Orientation" command="SetOrientation" number_of_elements="3"
    default_values="0 0 0"/>
<DoubleVectorProperty name="Scale" command="SetScale" number_of_elements="3" default_values="1 1 1"/>
<DoubleVectorProperty name="Origin" command="SetOrigin" number_of_elements="3" default_values="0 0 0"/>
"""
# The material's weights in [0, 1] and their defaults (ParaView's).
UNIT_PROPERTIES = (("Opacity", 1), ("Ambient", 0), ("Diffuse", 1), ("Specular", 0))


def unit_property_xml(name, default):
    return (f'<DoubleVectorProperty name="{name}" command="Set{name}" number_of_elements="1" '
            f'default_values="{default}"><DoubleRangeDomain name="range" min="0" max="1"/>'
            "</DoubleVectorProperty>")


# ParaView's representation lists that atoms can reach: polydata, and the unstructured grids of
# its Threshold and Extract Selection.
EXTENDED_REPRESENTATIONS = ("GeometryRepresentation", "UnstructuredGridRepresentation")


def representation_xml(spec, source_dir, core, mesolens):
    """The XML of a representation proxy and the entry that adds it to ParaView's list."""
    header = os.path.join(source_dir, spec["header"])
    mapper_header = os.path.join(source_dir, "Rendering", spec["mapper"] + ".h")
    mapper = getattr(mesolens, spec["mapper"])()
    brief, details = class_brief(header)
    wanted = spec["properties"]
    found = {name: (kind, value_type, doc, enums) for name, kind, value_type, doc, enums
             in properties_of(mapper_header, set())}
    missing = [name for name in wanted if name not in found]
    if missing:
        raise SystemExit(f"{spec['mapper']} has no properties {missing}")
    own = [xml_property(mapper, name, *found[name], spec, core)
           for name in wanted]
    exposed = "".join(f'<Property name="{name}"/>' for name in wanted)
    label = spec["label"]

    def extension(composite):
        """The entry that offers the representation in one of ParaView's representation lists."""
        return "\n".join([
            f'<Extension name="{composite}">',
            f'<RepresentationType subproxy="{spec["name"]}" text={quoteattr(label)}/>',
            f'<SubProxy><Proxy name="{spec["name"]}" proxygroup="representations" '
            f'proxyname="{spec["name"]}"/>'
            '<ShareProperties subproxy="SurfaceRepresentation"><Exception name="Input"/>'
            '<Exception name="Visibility"/></ShareProperties>'
            f"<ExposedProperties><PropertyGroup label={quoteattr(label)}>{exposed}"
            '<Hints><PropertyWidgetDecorator type="GenericDecorator" mode="visibility" '
            f'property="Representation" value={quoteattr(label)}/></Hints></PropertyGroup>'
            "</ExposedProperties></SubProxy>",
            "</Extension>"])

    return "\n".join([
        f'<RepresentationProxy name="{spec["name"]}" class="{spec["class"]}" '
        'processes="client|renderserver|dataserver">',
        f"<Documentation short_help={quoteattr(brief)}>{escape(details)}</Documentation>",
        SURFACE_PROPERTIES.strip(), *(unit_property_xml(*p) for p in UNIT_PROPERTIES), *own,
        "</RepresentationProxy>",
        *(extension(composite) for composite in EXTENDED_REPRESENTATIONS)])


def main():
    if len(sys.argv) != 4:
        raise SystemExit(__doc__)
    spec_path, source_dir, output = sys.argv[1:]
    spec = json.load(open(spec_path, encoding="utf-8"))
    import mesolens  # the built package: defaults and ranges come from the classes themselves
    core = CoreDocs(os.path.join(source_dir, "Core", "include"))
    groups = []
    for group in ("sources", "filters"):
        proxies = [proxy_xml(p, source_dir, core, mesolens) for p in spec.get(group, [])]
        groups.append(f'<ProxyGroup name="{group}">\n' + "\n".join(proxies) + "\n</ProxyGroup>")
    representations = [representation_xml(r, source_dir, core, mesolens)
                        for r in spec.get("representations", [])]
    if representations:
        groups.append('<ProxyGroup name="representations">\n' + "\n".join(representations)
                      + "\n</ProxyGroup>")
    text = ("<ServerManagerConfiguration>\n<!-- Generated by scripts/paraview_proxies.py from the "
            "class headers and ParaView/MesoLens/proxies.json; do not edit. -->\n"
            + "\n".join(groups) + "\n</ServerManagerConfiguration>\n")
    with open(output, "w", encoding="utf-8") as stream:
        stream.write(text)


if __name__ == "__main__":
    main()
