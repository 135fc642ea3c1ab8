"""The plugin's proxies as the ParaView 5.11 panel shows them (Plugins/ModelSynth/*.xml): every
property is of a kind the panel has a widget for (an IdTypeVectorProperty gets none, so a Seed
declared that way was invisible), every visible property has documentation (its tooltip), the
synthesis filters have a Seed, and every filter and source is in one ModelSynth menu."""
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
