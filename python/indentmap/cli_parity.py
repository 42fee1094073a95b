"""The one table of what the ``indentmap`` program's subcommands and options are in Python.

Every subcommand (``"indent"``, ``"render view3d"``) and every long option (``"indent --hardness"``) the
program's ``--help`` lists has one entry: ``Python(target, parameter)``, the function, class or method
(a dotted name in the ``indentmap`` package) and, for an option, the keyword parameter of its signature
that does the same; or ``Reason(text)``, why there is none. ``NOT_YET`` marks what Python cannot do yet
(issue 29; docs/python.md, "What Python cannot do yet"). python/tests/test_cli_parity.py walks the
program's help and fails for an option missing here, for a target or parameter that does not exist, and
for an entry whose subcommand or option the program no longer has: a new option needs a decision here.
"""
from typing import NamedTuple, Optional


class Python(NamedTuple):
    """The Python counterpart: ``target`` (dotted, within ``indentmap``) and its keyword ``parameter``."""
    target: str
    parameter: Optional[str] = None
    note: str = ""


class Reason(NamedTuple):
    """Why there is no Python counterpart."""
    text: str


NOT_YET = Reason("not yet in Python (issue 29)")
OUT = Reason("Python returns arrays and objects instead of writing files: save them with numpy or im.write")
CROP = Reason("slice the array: heights[y0:y0 + ny, x0:x0 + nx]")
SMOOTH = Reason("a flat surface is np.zeros((m, n))")
# The program's IM_RENDER_BACKEND is its own: Python opens 'auto' unless told.
BACKEND = Python("use_backend", note="once, for the pictures that follow")
NO_WISDOM = Reason("Python reads no FFTW wisdom file unless given one (wisdom=; None, the default, reads none)")
MPI = Reason("MPI runs are the program's (mpirun -n K indentmap mpi-indent); Python runs in one process")
PRINT = Reason("Python returns arrays; print or format them with numpy")
# render animate's frames are composed in src/cli/render.c from render's own option struct (its shared norm,
# the colour bar's extension triangles, the PNG texts) by the code that also writes render's figures; the
# library has the pieces (figure.h: im_figure_write_frame, im_animation_gif, im_animation_mp4), not the frames.
ANIMATE = Reason("draw each step with Figure([force], ...).save(path) (one shared vmax) and animate() the "
                 "pictures into a GIF, or run the program's render animate; its frame composition lives in "
                 "src/cli/render.c, not yet in the library")

PARITY = {
    # ---- surface: generate or measure ----
    "surface": Python("generate"),
    "surface --n": Python("generate", "n"),
    "surface --m": Python("generate", "m"),
    "surface --delta": Python("generate", "delta"),
    "surface --unit": Python("write", "unit", "the unit is written with the file; no conversion on reading"),
    "surface --height-unit": Python("read", "height_unit"),
    "surface --channel": Python("read", "channel"),
    "surface --fill": Python("read", "fill"),
    "surface --resample-square": Python("read", "resample_square"),
    "surface --crop": CROP,
    "surface --npy-order": Python("read", "npy_order"),
    "surface --detrend": Python("prepare", "detrend"),
    "surface --align": Python("prepare", "align"),
    "surface --window": Python("statistics", "window"),
    "surface --hurst": Python("generate", "hurst"),
    "surface --slope": Python("generate", "slope"),
    "surface --height-rms": Python("generate", "height_rms"),
    "surface --slope-def": Python("generate", "slope_definition"),
    "surface --lambda-s": Python("generate", "lambda_s"),
    "surface --lambda-r": Python("generate", "lambda_r"),
    "surface --lambda-0": Python("generate", "lambda_0"),
    "surface --seed": Python("generate", "seed"),
    "surface --out": Python("write"),
    "surface --stats": Python("statistics", note="of read(path).heights"),
    "surface --png": Python("height_map", note="Image.save writes the PNG"),
    "surface --psd": Python("psd"),
    "surface --histograms": Python("histogram"),
    # ---- theory ----
    "theory": Python("theory"),
    "theory --alpha": Python("theory.area_ratio", "alpha"),
    "theory --slope": Python("theory.area_ratio", "slope"),
    "theory --rho": Python("theory.beta", "rho"),
    "theory --gamma": Python("theory.gamma"),
    "theory --format": PRINT,
    "theory --normalisation": Python("theory.area_ratio", "normalisation"),
    "theory --k": Python("theory.area_ratio", "k"),
    "theory --punch": Python("theory.sphere_area", note="the sphere; the flat punch's ratio is not yet in Python"),
    "theory --radius": Python("theory.sphere_area", "radius"),
    "theory --load": Python("theory.sphere_area", "load"),
    "theory --fit-k": Python("theory.fit_k_history", "path"),
    # ---- indent ----
    "indent": Python("indent"),
    "indent --smooth": SMOOTH,
    "indent --n": SMOOTH,
    "indent --m": SMOOTH,
    "indent --delta": Python("Indentation", "delta"),
    "indent --unit": Python("read", "unit"),
    "indent --height-unit": Python("read", "height_unit"),
    "indent --channel": Python("read", "channel"),
    "indent --length-unit": Python("read", "length_unit", "then Indentation(length_unit=t.unit) for the records"),
    "indent --e-star-unit": Python("Indentation", "e_star_unit", "Indentation.units: run.json's units block"),
    "indent --fill": Python("read", "fill"),
    "indent --npy-order": Python("read", "npy_order"),
    "indent --resample-square": Python("read", "resample_square"),
    "indent --crop": CROP,
    "indent --detrend": Python("prepare", "detrend"),
    "indent --align": Python("prepare", "align"),
    "indent --punch": Python("indent", "punch", "Cone(), Sphere(R), Flat(a) or a profile array"),
    "indent --profile": Python("Indentation", "punch", "the profile as a numpy array (np.loadtxt or np.load)"),
    "indent --alpha": Python("Cone", "alpha"),
    "indent --radius": Python("Sphere", "radius", "Flat(radius) for the flat punch"),
    "indent --x": Python("Indentation", "axis"),
    "indent --y": Python("Indentation", "axis"),
    "indent --approach": Python("indent", "approaches"),
    "indent --load": Python("indent", "loads"),
    "indent --periodic": Python("Indentation", "periodic"),
    "indent --pressure": Python("indent", "pressures"),
    "indent --mean-gap": Python("indent", "mean_gaps"),
    "indent --slope-definition": Python("Indentation", "slope_definition"),
    "indent --e-star": Python("Indentation", "e_star"),
    "indent --hardness": Python("Indentation", "hardness"),
    "indent --adhesion-work": Python("Indentation", "adhesion_work"),
    "indent --adhesion-range": Python("Indentation", "adhesion_range"),
    "indent --adhesion-law": Python("Indentation", "adhesion_law"),
    "indent --adhesion-zone": Python("Indentation", "adhesion_zone"),
    "indent --quality": Python("Indentation", "quality"),
    "indent --tol": Python("Indentation", "tol"),
    "indent --max-iter": Python("Indentation", "max_iterations"),
    "indent --full": Python("Indentation", "crop", "crop=False solves on the whole surface"),
    "indent --plain-pk": Python("Indentation", "plain_pk"),
    "indent --device": Python("Indentation", "device"),
    "indent --measure": Python("Indentation", "measure"),
    "indent --wisdom": Python("Indentation", "wisdom"),
    "indent --no-wisdom": NO_WISDOM,
    "indent --out": Python("indent_run", "out", "the run's whole folder, as the program writes it"),
    "indent --fields": Python("indent", "fields"),
    "indent --frames": Python("indent_run", "frames"),
    "indent --page-embed": Python("indent_run", "page_embed"),
    "indent --distributions": Python("indent", "distributions", "Indentation.write_distributions for one step"),
    "indent --from-record": Reason("a Python indentation's run.json records no arguments to make it from again: "
                                   "the script that made it is its record (run it again); scenes have "
                                   "run_scene_from_record"),
    # ---- render ----
    "render": Python("Figure"),
    "render contact": Python("contact_map"),
    "render height": Python("height_map"),
    "render animate": ANIMATE,
    "render --out": Python("Figure.save", note="Image.save for one picture"),
    "render --raw": Python("contact_map", note="contact_map and height_map give the data image"),
    "render --colormap": Python("contact_map", "colormap"),
    "render --vmin": Python("contact_map", "vmin"),
    "render --vmax": Python("contact_map", "vmax"),
    "render --log": Python("contact_map", "log"),
    "render --linear": Python("contact_map", "log", "log=False"),
    "render --clip": Python("height_map", "clip"),
    "render --scale": Python("contact_map", "scale"),
    "render --circle": Python("contact_map", "circle_radius"),
    "render --circle-x": Python("contact_map", "circle_centre"),
    "render --circle-y": Python("contact_map", "circle_centre"),
    "render --contact": Python("height_map", "contact"),
    "render --label": Python("Figure", "labels"),
    "render --title": Python("Figure", "titles"),
    "render --titles": Python("Figure", "titles"),
    "render --columns": Python("Figure", "columns"),
    "render --quantity": Python("Figure", "colorbar_label"),
    "render --dpi": Python("Figure", "dpi"),
    "render --fps": Python("animate", "fps"),
    "render --frames": ANIMATE,
    "render --backend": BACKEND,
    # ---- render view3d: the 3-D view ----
    "render view3d": Python("view3d"),
    **{f"render view3d --{name}": Python("view3d", name.replace("-", "_")) for name in (
        "force", "displacement", "punch", "punch-mode", "azimuth", "elevation", "distance", "fov", "ortho",
        "ortho-height", "exaggeration", "width", "height", "samples", "mesh-side", "colormap", "vmin", "vmax",
        "log")},
    "render view3d --raw": Python("view3d", note="view3d returns the data image; Image.save writes it"),
    "render view3d --fill": Python("read", "fill", "im.read(path, fill=True).heights"),
    "render view3d --unit": Python("read", "unit"),
    "render view3d --height-unit": Python("read", "height_unit"),
    "render view3d --channel": Python("read", "channel"),
    "render view3d --npy-order": Python("read", "npy_order"),
    "render view3d --resample-square": Python("read", "resample_square"),
    "render view3d --crop": CROP,
    "render view3d --detrend": Python("prepare", "detrend"),
    "render view3d --align": Python("prepare", "align"),
    "render view3d --alpha": Python("Cone", "alpha"),
    "render view3d --radius": Python("Sphere", "radius", "Flat(radius) for the flat punch"),
    "render view3d --x": Python("view3d", "axis"),
    "render view3d --y": Python("view3d", "axis"),
    "render view3d --linear": Python("view3d", "log", "log=False"),
    # the figure around the 3-D image (colour bar, title, exaggeration stated)
    "render view3d --out": Python("View3DFigure", note="View3DFigure(...).save(path); view3d alone is --raw"),
    "render view3d --title": Python("View3DFigure", "title"),
    "render view3d --dpi": Python("View3DFigure", "dpi"),
    "render view3d --backend": BACKEND,
    # ---- run: scenes ----
    "run": Python("run_scene"),
    "run --resume": Python("run_scene", "resume"),
    "run --quiet": Python("run_scene", "quiet"),
    "run --backend": Python("run_scene", "backend"),
    "run --wisdom": Python("run_scene", "wisdom"),
    "run --no-wisdom": NO_WISDOM,
    "run --from-record": Python("run_scene_from_record"),
    "run --out": Python("run_scene", "out"),
    "run --check": Python("check_scene"),
    # ---- formats, info ----
    "formats": Python("formats"),
    "info": Python("info"),
    "info --backend": Python("info", "backend"),
    "info --memory": Python("solver_memory", "n", "one engine and mode per call: periodic=, device="),
    # ---- mpi-indent (in builds with MPI) ----
    "mpi-indent": MPI,
    **{f"mpi-indent --{name}": MPI for name in (
        "surface", "n", "m", "seed", "slope", "punch", "alpha", "radius", "approach", "load", "hardness", "tol",
        "max-iter", "out", "map", "periodic", "pressure", "mean-gap", "adhesion-work", "adhesion-range",
        "adhesion-law", "adhesion-zone", "profile", "frames")},
}

# Subcommands only some builds have: their entries may name what this build's program lacks.
OPTIONAL_COMMANDS = {"mpi-indent"}


def not_yet():
    """The entries Python cannot do yet, in the table's order."""
    return [key for key, value in PARITY.items() if value == NOT_YET]
