"""The plugin's proxies as the ParaView 5.11 panel shows them (Plugins/ModelSynth/*.xml): every
property is of a kind the panel has a widget for (an IdTypeVectorProperty gets none, so a Seed
declared that way was invisible), every property has documentation (the tooltip of those shown),
every shown property a label of its own, check boxes set one value each (a check box sets only the
first of several), the boundary faces are named check boxes, the synthesis filters have a Seed,
and every filter and source is in one ModelSynth menu."""
import re
import glob
import os
import unittest
import xml.etree.ElementTree as ET

PLUGIN = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Plugins", "ModelSynth")
SHOWN = {"IntVectorProperty", "DoubleVectorProperty", "StringVectorProperty", "InputProperty",
         "ProxyProperty"}


def proxies():
    """(file, group, proxy element) of every proxy the plugin declares."""
    for path in sorted(glob.glob(os.path.join(PLUGIN, "*.xml"))):
        root = ET.parse(path).getroot()
        for group in root.iter("ProxyGroup"):
            for proxy in group:
                yield os.path.basename(path), group.get("name"), proxy


class PluginXmlTest(unittest.TestCase):
    def test_every_property_has_a_widget_and_a_tooltip(self):
        seen, missing = 0, []
        for name, group, proxy in proxies():
            for prop in proxy:
                if not prop.tag.endswith("Property"):
                    continue
                seen += 1
                where = "%s %s.%s" % (name, proxy.get("name"), prop.get("name"))
                if prop.get("information_only") == "1":
                    continue
                self.assertIn(prop.tag, SHOWN, where + ": the panel has no widget for " + prop.tag)
                if prop.get("panel_visibility") == "never" or (group == "writers" and prop.tag == "InputProperty"):
                    continue  # not shown (a writer's input is the data being saved)
                doc = prop.find("Documentation")
                if doc is None or not (doc.text or "").strip():
                    missing.append(where)
        self.assertGreater(seen, 100)
        self.assertEqual(missing, [], "properties without a tooltip")

    def test_every_property_is_documented_and_labelled(self):
        undocumented, unlabelled, shared = [], [], []
        for name, group, proxy in proxies():
            labels = {}
            for prop in proxy:
                if not prop.tag.endswith("Property"):
                    continue
                where = "%s %s.%s" % (name, proxy.get("name"), prop.get("name"))
                doc = prop.find("Documentation")
                if doc is None or not (doc.text or "").strip():
                    undocumented.append(where)
                if prop.get("information_only") == "1" or prop.get("panel_visibility") == "never":
                    continue
                # ParaView labels a property by its label attribute, else its name split into words.
                label = prop.get("label")
                if label is None:
                    label = re.sub(r"(?<=[a-z0-9])(?=[A-Z])", " ", prop.get("name") or "")
                # paraview.simple names the property after its label, letters and digits only.
                python = re.sub(r"[^A-Za-z0-9]", "", label)
                if not python:
                    unlabelled.append(where)
                elif python in labels and prop.get("override") != "1":
                    shared.append("%s and %s: %r" % (labels[python], where, python))
                labels[python] = where
        self.assertEqual(undocumented, [], "properties without documentation")
        self.assertEqual(unlabelled, [], "properties shown without a label")
        self.assertEqual(shared, [], "two properties of one proxy with one label (one Python name)")

    def test_check_boxes_set_one_value(self):
        """A BooleanDomain is one check box, linked to the first element only."""
        for name, group, proxy in proxies():
            for prop in proxy:
                if prop.find("BooleanDomain") is not None:
                    self.assertEqual(prop.get("number_of_elements"), "1", "%s %s.%s: a check box for %s values" % (
                        name, proxy.get("name"), prop.get("name"), prop.get("number_of_elements")))

    def test_boundary_faces_are_named_check_boxes(self):
        """UseBoundary (six 0/1 flags for scripts) is hidden; the panel shows a check box per face."""
        found = 0
        for name, group, proxy in proxies():
            props = {p.get("name"): p for p in proxy if p.tag.endswith("Property")}
            if "UseBoundary" not in props:
                continue
            found += 1
            self.assertEqual(props["UseBoundary"].get("panel_visibility"), "never", proxy.get("name"))
            for face in ("XMin", "XMax", "YMin", "YMax", "ZMin", "ZMax"):
                box = props.get("Boundary" + face)
                self.assertIsNotNone(box, "%s: no check box for face %s" % (proxy.get("name"), face))
                self.assertEqual(box.get("command"), "SetBoundary" + face)
                self.assertIsNotNone(box.find("BooleanDomain"))
                self.assertEqual(box.get("label"), "Boundary %s %s" % (face[0], face[1:]))
            self.assertIn("-X +X, -Y +Y, -Z +Z", " ".join(props["BoundaryLabels"].find("Documentation").text.split()))
        self.assertGreater(found, 0)

    def test_tile_image_takes_the_inputs_tileset(self):
        for name, group, proxy in proxies():
            if proxy.get("name") == "MSTileImage":
                tileset = next(p for p in proxy if p.get("name") == "TilesetFile")
                self.assertEqual(tileset.get("default_values"), "", "TilesetFile may stay empty")
                self.assertIn("input", tileset.find("Documentation").text)
                return
        self.fail("no MSTileImage proxy")

    def test_synthesis_filters_have_a_seed(self):
        names = {}
        for name, group, proxy in proxies():
            names[proxy.get("name")] = {p.get("name") for p in proxy if p.tag.endswith("Property")}
        for proxy in ("MSContinuousSynthesis", "MSDiscreteSynthesisBase", "MSPatternSynthesis",
                      "MSTimeVaryingSynthesis"):
            self.assertIn("Seed", names[proxy], proxy)

    def test_one_modelsynth_menu(self):
        for name, group, proxy in proxies():
            if group not in ("filters", "sources") or proxy.tag != "SourceProxy":
                continue
            if proxy.find("Hints/ReaderFactory") is not None:
                continue  # readers: File > Open
            menu = proxy.find("Hints/ShowInMenu")
            self.assertIsNotNone(menu, "%s %s is in no menu" % (name, proxy.get("name")))
            self.assertEqual(menu.get("category"), "ModelSynth", proxy.get("name"))


if __name__ == "__main__":
    unittest.main()
