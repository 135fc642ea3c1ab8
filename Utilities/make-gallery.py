"""Makes the gallery (Documentation/gallery.md): every bundled example of every kind, synthesized
with the command shown beside its preview. Run from the repository root after building:

    pvpython Utilities/make-gallery.py [NAME ...]

Each command runs as written (outputs in output/gallery/NAME); previews go to
Documentation/images/gallery/NAME.png: meshes and models rendered offscreen (render-model.py, on
a private Xvfb when there is no display), pictures copied, and an animation's frames stacked top
to bottom. Documentation/images/image-samples.png (guide-tilesets.md) is composed from the
meadow and rooms pictures, and the continuous guide's continuous-houses.png and
continuous-networks.png are rendered from the entries RENDERED_PICTURES names. With names, only
those entries (and the pictures made from them) are remade (the page lists all). A continuous
model's caption ends with its structure against the example (statistics.json's Resemblance: how
many of the measures of `msynth check` are within bounds, and the ones out), kept in
Documentation/images/gallery/structure.json between runs."""
import glob
import json
import os
import shutil
import subprocess
import sys



def render_model():
    """Utilities/render-model.py, imported when pictures are made (it needs paraview.simple)."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from xserver import ensure_display
    ensure_display()
    return __import__("render-model")

M = "build/bin/msynth"
D = "Data/Continuous"
# name, kind of example, what it shows, command (after "msynth"), preview
ENTRIES = [
    ("village-houses", "MagicaVoxel (.vox)", "The main job: one house whose wall labels name their "
     "side keeps houses rectangular and apart; labels by resemblance (M07)",
     "synthesize Data/Examples/Houses.vox --size 48 48 5 --block 12 12 5 --ground 1 --empty 0 "
     "--choice resemblance --seed 1", "mesh"),
    ("village", "Label grid (.vti)", "Discrete synthesis in blocks, ground below and empty space "
     "around (dissertation ch. 3)", "synthesize Data/Examples/Village.vti --size 48 48 5 "
     "--block 12 12 5 --ground 1 --empty 0 --seed 7", "mesh"),
    ("village-vox", "MagicaVoxel (.vox)", "The same village as MagicaVoxel writes it, ground "
     "(1) below and air (0) around", "synthesize Data/Examples/Village.vox --size 32 32 5 "
     "--block 16 16 5 --ground 1 --empty 0 --seed 2", "mesh"),
    ("lines", "Simple-tiled tileset (.xml)", "WaveFunctionCollapse's tileset format, 3 tiles",
     "synthesize Data/Tilesets/Lines.xml --size 24 16 1 --order entropy --choice frequency "
     "--seed 3", "picture"),
    ("lines-completed", "Simple-tiled tileset + drawn map (.png)", "A map drawn in a paint "
     "program with the tiles' images (Data/Tilesets/lines-drawn.png: two drawn patches, "
     "transparent elsewhere) completed; every drawn tile is kept",
     "synthesize Data/Tilesets/Lines.xml --size 24 24 1 --fixed Data/Tilesets/lines-drawn.png "
     "--seed 2", "picture"),
    ("lines-counted", "Simple-tiled tileset + counts", "100 to 150 corner tiles and 200 to 400 "
     "empty ones (of 576), in 12 × 12 blocks",
     "synthesize Data/Tilesets/Lines.xml --size 24 24 1 --block 12 12 1 --count corner:100:150 "
     "--count empty:200:400 --seed 1", "picture"),
    ("voxel-pipes", "Voxel tileset (MarkovJunior .xml + .vox tiles)", "4 voxel tiles under the cube's 48 "
     "symmetries (85 images), closed by empty faces; model.vox and the coloured mesh",
     "synthesize Data/Tilesets/Pipes.xml --size 12 12 6 --block 6 6 6 --empty 0 --choice frequency "
     "--seed 5", "mesh"),
    ("voxel-tracks", "Voxel tileset, 2D", "4 tiles one voxel high under the square's 8 symmetries; the "
     "view from above", "synthesize Data/Tilesets/Tracks.xml --size 24 16 1 --seed 2", "picture"),
    ("meadow", "Image sample (.png)", "Overlapping 3 × 3 windows, ground row, repeating in x",
     "synthesize Data/Samples/Meadow.png --pattern 3 --symmetry 2 --ground --translate x "
     "--size 192 64 1 --block 32 32 1 --choice frequency --seed 4", "picture"),
    ("rooms", "Image sample (.png)", "Rooms, fewest choices first",
     "synthesize Data/Samples/Rooms.png --size 128 128 1 --block 32 32 1 --order entropy --seed 2",
     "picture"),
    ("ball", "Time-varying (.vti, z = time)", "Balls rolling right one site a frame as the "
     "example's one ball does, 9 or 10 in each of 24 frames of a 32-site row, looping "
     "(dissertation §3.5.4); frames top to bottom",
     "animate Data/Examples/Ball.vti --size 32 1 1 --frames 24 --loop --seed 1", "frames"),
    ("houses", "Polyhedral (.obj)", "Continuous synthesis, no constraints: houses float",
     "synthesize %s/house.obj --size 24 24 10 --seed 3" % D, "model"),
    ("houses-constrained", "Polyhedral (.obj)", "Grounded, walls one storey and in whole "
     "2-spacing slabs across x and y (no posts), eaves one spacing, mirrored across x and y",
     "synthesize %s/house.obj --size 24 24 10 --seed 3 --grounded --thickness wall:z --overhang roof "
     "--thickness wall:x:2+ --thickness wall:y:2+ --mirror xy" % D, "model"),
    ("house-blender", "Blender OBJ export (y up)", "The house as Blender exports it by default, "
     "read with --up y", "synthesize %s/house-blender.obj --up y --size 24 24 10 --seed 3 "
     "--grounded --thickness Wall:z --overhang Roof" % D, "model"),
    ("cottages", "Polyhedral (.obj)", "Four object types (a chimney against the gable, a porch), "
     "grounded, walls 2 spacings high and in whole 2-spacing slabs across x and y, eaves one spacing, "
     "blocks of 8 spacings (a cottage does not fit the default 4)",
     "synthesize %s/cottage.obj --size 24 24 8 --seed 5 --grounded --thickness wall:z:2 "
     "--overhang roof --thickness wall:x:2+ --thickness wall:y:2+ --blocks 8" % D, "model"),
    ("oil", "Polyhedral (.obj)", "Decks one unit thick at several heights on beams, as the "
     "example's two decks stand, each deck at least 2 spacings wide, grown from the ground "
     "(--connected solid:3: at most three seeds)",
     "synthesize %s/oil-platform.obj --size 24 24 12 --seed 2 --grounded --blocks 0 "
     "--thickness platform:z --thickness platform:x:2+ --thickness platform:y:2+ "
     "--thickness beam:x --thickness beam:y --connected solid:3" % D,
     "model"),
    ("roads", "Polyhedral, 2D (.obj)", "One road network from one seed, one lane wide",
     "synthesize %s/roads.obj --size 40 40 0 --seed 1 --blocks 0 --connected road:1 "
     "--thickness road:xy" % D, "top"),
    ("pipes", "Polyhedral (.obj)", "One pipe network, one spacing across",
     "synthesize %s/pipes.obj --size 24 24 12 --seed 1 --blocks 0 --connected pipe:1 "
     "--thickness pipe:xy --thickness pipe:yz --thickness pipe:xz" % D, "model"),
    ("domes", "Polyhedral + detail (.obj)", "Hemispheres substituted into bounding volumes",
     "synthesize %s/domed-building.obj --size 24 24 10 --seed 2 --grounded "
     "--detail dome=%s/dome.obj" % (D, D), "model"),
    ("silos", "Polyhedral + detail (.obj)", "Cylinders in boxes cut into two prisms",
     "synthesize %s/silo.obj --size 16 16 8 --seed 3 --grounded "
     "--detail silo+silo2=%s/cylinder.obj" % (D, D), "model"),
    ("town", "Polyhedral + detail (.obj)", "A 474-polygon town block (houses, shops, roads, trees "
     "as bounding volumes) at 100 x 100 x 10: storeys, slabs one spacing thick, trees one spacing "
     "across with tree.obj substituted (about 35 s and 1.3 GB on two shared cores)",
     "synthesize %s/town.obj --size 100 100 10 --seed 1 --grounded --thickness wall:z:4 "
     "--thickness shop:z:6 --thickness shoproof:z --thickness road:z --thickness tree:x "
     "--thickness tree:y --detail tree=%s/tree.obj" % (D, D), "model"),
    ("pyramids", "Polyhedral (.obj)", "Four planes at every apex (TVCG §4.4)",
     "synthesize %s/pyramid.obj --size 20 20 6 --seed 1 --grounded" % D, "model"),
    ("octahedra", "Polyhedral (.obj)", "Four planes at the top and bottom vertices",
     "synthesize %s/octahedron.obj --size 16 16 8 --seed 1" % D, "model"),
    ("letters", "Polyhedral + guide (.vti)", "Houses only where the guide spells \"MS\"",
     "synthesize %s/house.obj --size 100 56 6 --seed 1 --grounded --thickness wall:z "
     "--guide %s/letters-guide.vti" % (D, D), "top"),
    ("facade", "Pattern exemplars (.vti)", "Factor-graph synthesis (BLOCKSS) with zones",
     "pattern Data/Patterns/facade-rectangular.vti Data/Patterns/facade-l-shaped.vti --size 28 18 "
     "--factors 2H,2V,4H,4V --zones Data/Patterns/facade-l-zones.vti --zone-tiles 0:1,2,3,4,5,6,7,9 "
     "--zone-tiles 1:0 --zone-tiles 2:8 --zone-tiles 3:9 --tileset Data/Patterns/Facade.xml --seed 1",
     "picture"),
    ("city", "Pattern exemplars (.vti)", "A city with a crossroad fixed every 20 tiles",
     "pattern Data/Patterns/city-suburban.vti Data/Patterns/city-urban.vti --size 170 170 "
     "--fixed Data/Patterns/city-crossroads-170.vti --tileset Data/Patterns/City.xml --seed 1",
     "picture"),
    ("city-roads", "Pattern exemplars (.vti)", "The same city with its roads one network "
     "(--connected: labels 1-15 are the road tiles)",
     "pattern Data/Patterns/city-suburban.vti Data/Patterns/city-urban.vti --size 170 170 "
     "--fixed Data/Patterns/city-crossroads-170.vti --tileset Data/Patterns/City.xml --seed 1 "
     "--connected 1,2,3,4,5,6,7,8,9,10,11,12,13,14,15", "picture"),
    ("border", "Pattern exemplar (.vti)", "A mirrored border around a free middle",
     "pattern Data/Patterns/border.vti --size 24 16 --factors 2H,2V,3x3 "
     "--zones Data/Patterns/border-zones.vti --zone-tiles 1:1,2,3,4,5,6,7,8 --zone-tiles 0:0 "
     "--zone-tiles 2:0,9,10,11 --mirror x --swap 3:4 --swap 5:6 --swap 7:8 --swap 10:11 "
     "--tileset Data/Patterns/Border.xml --seed 2", "picture"),
]

# Entries whose run takes minutes: test_gallery runs their command with this size instead.
QUICK_SIZES = {"town": "24 24 6"}


def frames_picture(folder, png):
    """The frames of an animation (frame_0001.vti ..., one row of sites each) stacked top to
    bottom, each site a square of 8 pixels, labels coloured as render-model.py colours them."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLImageDataReader
    import numpy as np
    rows = []
    for path in sorted(glob.glob(os.path.join(folder, "frame_*.vti"))):
        reader = vtkXMLImageDataReader()
        reader.SetFileName(path)
        reader.Update()
        rows.append(vtk_to_numpy(reader.GetOutput().GetPointData().GetArray("Label")).copy())
    labels = np.array(rows)
    palette = render_model().COLOURS + render_model().MORE
    colours = np.array([[255, 255, 255]] + [[int(255 * c) for c in palette[3 * i:3 * i + 3]]
                                            for i in range(12)], dtype=np.uint8)
    rgb = colours[np.clip(labels, 0, 12)]
    write_png(np.repeat(np.repeat(rgb, 8, axis=0), 8, axis=1), png)


def read_png(path):
    """The RGB pixels of the PNG @p path, top row first."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOImage import vtkPNGReader
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(height, width, -1)
    return pixels[::-1, :, :3]


def write_png(rgb, path):
    """Writes the RGB pixels @p rgb (top row first) to the PNG @p path."""
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkIOImage import vtkPNGWriter
    import numpy as np
    rgb = np.ascontiguousarray(rgb[::-1])  # VTK rows: bottom first
    image = vtkImageData()
    image.SetDimensions(rgb.shape[1], rgb.shape[0], 1)
    image.GetPointData().SetScalars(numpy_to_vtk(rgb.reshape(-1, 3), deep=1))
    writer = vtkPNGWriter()
    writer.SetInputData(image)
    writer.SetFileName(path)
    writer.Write()


# Documentation/images/image-samples.png (guide-tilesets.md): these entries' pictures, each pixel
# a square of SAMPLES_SCALE pixels, one above the other, centred on white, 8 pixels apart.
SAMPLES_PICTURE = ("meadow", "rooms")
SAMPLES_SCALE = 3


def samples_picture(png):
    """The guide's picture of image samples from the gallery's outputs of SAMPLES_PICTURE."""
    import numpy as np
    parts = [np.repeat(np.repeat(read_png(os.path.join("output", "gallery", name, "picture.png")),
                                 SAMPLES_SCALE, axis=0), SAMPLES_SCALE, axis=1)
             for name in SAMPLES_PICTURE]
    width = max(p.shape[1] for p in parts)
    rgb = np.full((sum(p.shape[0] for p in parts) + 8 * (len(parts) - 1), width, 3), 255, np.uint8)
    y = 0
    for p in parts:
        x = (width - p.shape[1]) // 2
        rgb[y:y + p.shape[0], x:x + p.shape[1]] = p
        y += p.shape[0] + 8
    write_png(rgb, png)


# The continuous guide's pictures (Documentation/images/NAME) rendered from these entries'
# models, side by side, each (width, height) pixels; True: seen from above.
RENDERED_PICTURES = [
    ("continuous-houses.png", [("houses", False)], (900, 700)),
    ("continuous-networks.png", [("roads", True), ("pipes", False), ("silos", False),
                                 ("oil", False)], (500, 500)),
]


def rendered_picture(png, panels, size):
    """@p panels (entry, top view) rendered from the gallery's outputs and put side by side."""
    import numpy as np
    parts = []
    for k, (name, top) in enumerate(panels):
        panel = "%s.panel%d.png" % (png, k)
        render_model().render(os.path.join("output", "gallery", name, "model.vtp"), panel, top=top,
                              size=size)
        parts.append(read_png(panel))
        os.remove(panel)
    write_png(np.concatenate(parts, axis=1), png)


def main(names):
    images = os.path.join("Documentation", "images", "gallery")
    os.makedirs(images, exist_ok=True)
    for name, kind, what, command, preview in ENTRIES:
        if names and name not in names:
            continue
        out = os.path.join("output", "gallery", name)
        os.makedirs(os.path.dirname(out), exist_ok=True)
        done = subprocess.run([M] + command.split() + ["--out", out], capture_output=True, text=True)
        if done.returncode != 0:
            sys.exit("%s: %s" % (name, done.stderr.strip()))
        record_structure(name, os.path.join(out, "statistics.json"))
        png = os.path.join(images, name + ".png")
        if preview == "picture":
            shutil.copyfile(os.path.join(out, "picture.png"), png)
        elif preview == "frames":
            frames_picture(out, png)
        else:
            model = os.path.join(out, "mesh.vtp" if preview == "mesh" else "model.vtp")
            render_model().render(model, png, top=preview == "top", size=(480, 360))
        print("made", png)
    if not names or any(name in names for name in SAMPLES_PICTURE):
        png = os.path.join("Documentation", "images", "image-samples.png")
        samples_picture(png)
        print("made", png)
    for picture, panels, size in RENDERED_PICTURES:
        if not names or any(name in names for name, top in panels):
            png = os.path.join("Documentation", "images", picture)
            rendered_picture(png, panels, size)
            print("made", png)
    write_page()


STRUCTURE = os.path.join("Documentation", "images", "gallery", "structure.json")


def load_structure():
    if not os.path.exists(STRUCTURE):
        return {}
    with open(STRUCTURE) as f:
        return json.load(f)


def record_structure(name, statistics):
    """Keeps the entry's structure summary (continuous models) for its caption."""
    with open(statistics) as f:
        measures = json.load(f).get("Resemblance")
    kept = load_structure()
    kept.pop(name, None)
    if measures:
        out = ["%s %.3g (example %.3g)" % (m["measure"], m["model"], m["example"])
               for m in measures if not m["passes"]]
        kept[name] = "structure against the example: %d of %d measures within bounds%s" % (
            len(measures) - len(out), len(measures), "; out: " + ", ".join(out) if out else "")
    with open(STRUCTURE, "w") as f:
        json.dump(kept, f, indent=1, sort_keys=True)
        f.write("\n")


def write_page():
    """Documentation/gallery.md from ENTRIES."""
    with open(os.path.join("Documentation", "gallery.md"), "w") as f:
        f.write("# Gallery\n\nEvery bundled example, synthesized by the command beside it (run "
                "from the repository root after building; add `--out DIR`). The pictures are "
                "made by `pvpython Utilities/make-gallery.py`, which runs these "
                "commands and renders their outputs.\n\n")
        f.write("| preview | example | command |\n|---|---|---|\n")
        structure = load_structure()
        for name, kind, what, command, preview in ENTRIES:
            if name in structure:
                what += " (%s)" % structure[name]
            f.write("| ![%s](images/gallery/%s.png) | **%s** (%s): %s | `build/bin/msynth %s` |\n" % (
                name, name, name, kind, what, command))


if __name__ == "__main__":
    main(sys.argv[1:])
