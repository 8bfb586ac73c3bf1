#!/usr/bin/env python3
"""Writes tests/data/gldf/PendantTwoEmitters.gldf: a GLDF container whose variant places two
emitters at the two light-emitting objects of the L3D example_004 (a pendant: leo_bottom emits
down, leo_top up), both with the EULUMDAT photometry of gldf.net's GldfWithFilesComplete.gldf.
Packed with Python's zipfile (not Candela's code). Both sources are MIT, (c) 2021 DIAL - RELUX.

Usage: tools/make_pendant_gldf.py (from the repository root)."""
import io
import zipfile

ROOT = "tests/data"
PRODUCT = """<?xml version="1.0" encoding="utf-8"?>
<Root>
  <Header>
    <Manufacturer>Candela tests</Manufacturer><FormatVersion major="1" minor="0"/>
    <CreatedWithApplication>tools/make_pendant_gldf.py</CreatedWithApplication>
    <GldfCreationTimeCode>2026-11-26T00:00:00Z</GldfCreationTimeCode><UniqueGldfId>pendant</UniqueGldfId>
  </Header>
  <GeneralDefinitions>
    <Files>
      <File id="ldt" contentType="ldc/eulumdat" type="localFileName">pendant.ldt</File>
      <File id="geo" contentType="geo/l3d" type="localFileName">pendant.l3d</File>
    </Files>
    <Photometries><Photometry id="p"><PhotometryFileReference fileId="ldt"/></Photometry></Photometries>
    <Emitters>
      <Emitter id="down"><FixedLightEmitter><PhotometryReference photometryId="p"/></FixedLightEmitter></Emitter>
      <Emitter id="up"><FixedLightEmitter><PhotometryReference photometryId="p"/></FixedLightEmitter></Emitter>
    </Emitters>
    <Geometries><ModelGeometry id="model"><GeometryFileReference fileId="geo"/></ModelGeometry></Geometries>
  </GeneralDefinitions>
  <ProductDefinitions>
    <ProductMetaData><UniqueProductId>pendant</UniqueProductId>
      <ProductNumber><Locale language="en">PENDANT-2</Locale></ProductNumber>
      <Name><Locale language="en">Pendant, direct and indirect</Locale></Name>
    </ProductMetaData>
    <Variants><Variant id="pendant"><Name><Locale language="en">Pendant</Locale></Name>
      <Geometry><ModelGeometryReference geometryId="model">
        <EmitterReference emitterId="down"><EmitterObjectExternalName>leo_bottom</EmitterObjectExternalName></EmitterReference>
        <EmitterReference emitterId="up"><EmitterObjectExternalName>leo_top</EmitterObjectExternalName></EmitterReference>
      </ModelGeometryReference></Geometry></Variant></Variants>
  </ProductDefinitions>
</Root>
"""


def main():
    example = ROOT + "/l3d/examples/example_004/"
    l3d = io.BytesIO()
    with zipfile.ZipFile(l3d, "w", zipfile.ZIP_DEFLATED) as z:
        z.write(example + "structure.xml", "structure.xml")
        z.write(example + "luminaire/luminaire.obj", "luminaire/luminaire.obj")
    ldt = zipfile.ZipFile(ROOT + "/gldf/GldfWithFilesComplete.gldf").read("ldc/photometry.ldt")
    with zipfile.ZipFile(ROOT + "/gldf/PendantTwoEmitters.gldf", "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("product.xml", PRODUCT)
        z.writestr("ldc/pendant.ldt", ldt)
        z.writestr("geo/pendant.l3d", l3d.getvalue())


if __name__ == "__main__":
    main()
