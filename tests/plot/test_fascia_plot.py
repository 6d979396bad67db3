"""fascia-plot (apps/fascia-plot, docs/viewer.md "Plots: fascia-plot"): the PNG it writes has its
axes and its lines, the lines it draws are the CSV's values, and every bad input gives its one-line
message and exit code, with nothing written. Run by ctest as plot_fascia_plot (FASCIA_PLOT names the
build's copy of the script; without it, the source's is run).

The pixel checks read the PNG back, find the axes frame from its black spines (not from what the
tool says), map each pixel column of a line's colour back to data coordinates through that frame
and the axis limits, and compare it with the CSV's values interpolated there. Each such check is
also run against a wrong column, where it must fail, so that it is seen to be able to.
"""
import csv
import json
import math
import os
import resource
import stat
import struct
import subprocess

import numpy as np
import pytest

SOURCE = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
TOOL = os.environ.get("FASCIA_PLOT") or os.path.join(SOURCE, "apps", "fascia-plot", "fascia-plot")
# a real Monitor file: the palpation probe's force and torque (tests/plot/README.md)
PALPATION = os.path.join(SOURCE, "tests", "plot", "data", "palpation_probe.csv")
BLUE, ORANGE = (0x1f, 0x77, 0xb4), (0xff, 0x7f, 0x0e)  # matplotlib's first two line colours
TOL_PX = 2.0        # a drawn value may be this far from the CSV's, in pixels
HALF_WIDTH_PX = 1.5  # half the line's width (1.5 pt at 100 dpi is 2.1 px) with its antialiased edge


@pytest.fixture(autouse=True)
def _in_tmp(tmp_path, monkeypatch):
    """Every test runs in its own folder: outputs never land in the source tree."""
    monkeypatch.chdir(tmp_path)


def run(*args, limit_file_size=None, env=None):
    def limits():
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit_file_size, resource.getrlimit(resource.RLIMIT_FSIZE)[1]))
    return subprocess.run([TOOL, *map(str, args)], capture_output=True, text=True, timeout=120,
                          env=dict(os.environ, **env) if env else None,
                          preexec_fn=limits if limit_file_size is not None else None)


def run_ok(*args, env=None):
    p = run(*args, env=env)
    assert p.returncode == 0, p.stderr
    assert p.stderr == ""
    return p


def write_csv(path, header, rows):
    with open(path, "w") as f:
        f.write(",".join(header) + "\n")
        for r in rows:
            f.write(",".join(repr(float(v)) if not isinstance(v, str) else v for v in r) + "\n")
    return path


def read_csv(path):
    """{column name without its unit: numpy array}, read here (not by the tool)."""
    with open(path) as f:
        rows = list(csv.reader(f))
    names = [h.rsplit(" [", 1)[0] for h in rows[0]]
    data = np.array([[float(v) for v in r] for r in rows[1:]])
    return {n: data[:, k] for k, n in enumerate(names)}


# ---- reading the PNG

def png_size(path):
    """Width and height from the PNG's IHDR chunk, read from the bytes."""
    with open(path, "rb") as f:
        head = f.read(24)
    assert head[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    assert head[12:16] == b"IHDR"
    return struct.unpack(">II", head[16:24])


def pixels(path):
    """The image as rows of RGB in [0, 1] (Pillow, which Debian's matplotlib depends on)."""
    from PIL import Image
    with Image.open(path) as img:
        return np.asarray(img.convert("RGB"), dtype=float) / 255.0


def runs_along(mask):
    """For each column of mask, its longest run of True along axis 0."""
    best = np.zeros(mask.shape[1], int)
    cur = np.zeros(mask.shape[1], int)
    for row in mask:
        cur = np.where(row, cur + 1, 0)
        best = np.maximum(best, cur)
    return best


def clusters(indices):
    """Runs of adjacent indices, each as its centre in pixel coordinates (index + 0.5)."""
    out, group = [], []
    for i in indices:
        if group and i != group[-1] + 1:
            out.append(np.mean(group) + 0.5)
            group = []
        group.append(i)
    if group:
        out.append(np.mean(group) + 0.5)
    return out


def axes_frame(rgb):
    """(left, top, right, bottom) of the axes frame in pixels from the image's top-left corner: the
    black lines (every channel below 0.35, so no line colour or grey grid) longer than half the image."""
    h, w, _ = rgb.shape
    black = rgb.max(axis=2) < 0.35
    vertical = clusters(np.nonzero(runs_along(black) > 0.5 * h)[0])
    horizontal = clusters(np.nonzero(runs_along(black.T) > 0.5 * w)[0])
    assert len(vertical) == 2, f"expected the left and right spines, found vertical black lines at {vertical}"
    assert len(horizontal) == 2, f"expected the top and bottom spines, found horizontal black lines at {horizontal}"
    return vertical[0], horizontal[0], vertical[1], horizontal[1]


def frame_of(rgb, report):
    """The axes box the report gives (exact: the spines are drawn snapped to whole pixels), checked to be
    where the image's spines are, within a pixel."""
    found = axes_frame(rgb)
    box = report["axes_px"]
    said = box["left"], box["top"], box["right"], box["bottom"]
    for name, f, s in zip(("left", "top", "right", "bottom"), found, said):
        assert abs(f - s) <= 1.0, f"the {name} spine is at {f}, the report says {s}"
    return said


def of_colour(rgb, colour, within=0.25):
    return np.linalg.norm(rgb - np.array(colour) / 255.0, axis=2) < within


def line_mismatches(rgb, frame, xlim, ylim, xs, ys, colour, exclude=None, others=()):
    """Compares the pixels of `colour` inside the frame with the curve (xs, ys), xs increasing, column by
    column of pixels: the curve's value at the column's centre must lie among the column's drawn pixels,
    and every drawn pixel must be near the curve over the column (within TOL_PX and the line's half width).
    Columns where a curve of `others` (drawn over this one) comes within 8 px are left out.
    Returns (columns compared, list of mismatches)."""
    left, top, right, bottom = frame
    mask = of_colour(rgb, colour)
    if exclude:  # the legend, which holds a sample of each line
        mask[int(exclude["top"]) - 3:int(math.ceil(exclude["bottom"])) + 3,
             int(exclude["left"]) - 3:int(math.ceil(exclude["right"])) + 3] = False

    def x_of(px):
        return xlim[0] + (px - left) / (right - left) * (xlim[1] - xlim[0])

    def row_of(y):
        return bottom - (np.asarray(y) - ylim[0]) / (ylim[1] - ylim[0]) * (bottom - top)

    def reach(c, xs, ys):  # the rows a curve covers over column c and its neighbours
        a, b = x_of(c - 1.5), x_of(c + 2.5)
        window = np.concatenate([np.linspace(a, b, 31), xs[(xs >= a) & (xs <= b)]])
        r = row_of(np.interp(window, xs, ys))
        return r.min(), r.max()

    compared, bad = 0, []
    for c in range(int(math.ceil(left)) + 1, int(right) - 1):
        xc = x_of(c + 0.5)
        if xc < xs[0] or xc > xs[-1]:
            continue
        rmin, rmax = reach(c, xs, ys)
        if any(omin - 8 < rmax and omax + 8 > rmin for omin, omax in (reach(c, ox, oy) for ox, oy in others)):
            continue
        compared += 1
        rows = np.nonzero(mask[int(top) + 1:int(bottom), c])[0] + int(top) + 1
        if rows.size == 0:
            bad.append(f"column {c} (x = {xc:.6g}): no pixel of the line")
            continue
        lo, hi = rows.min() + 0.5, rows.max() + 0.5
        expected = float(row_of(np.interp(xc, xs, ys)))
        if not lo - TOL_PX <= expected <= hi + TOL_PX:
            bad.append(f"column {c} (x = {xc:.6g}): the CSV's value is at row {expected:.1f}, the line at rows {lo:.1f} to {hi:.1f}")
        elif lo < rmin - TOL_PX - HALF_WIDTH_PX or hi > rmax + TOL_PX + HALF_WIDTH_PX:
            bad.append(f"column {c} (x = {xc:.6g}): the line spans rows {lo:.1f} to {hi:.1f}, the CSV's curve "
                       f"{rmin:.1f} to {rmax:.1f} there")
    return compared, bad


def assert_draws(rgb, frame, xlim, ylim, xs, ys, colour, exclude=None, others=(), least=0.9, what=""):
    """The line of `colour` draws (xs, ys) on at least the fraction `least` of the frame's pixel columns."""
    compared, bad = line_mismatches(rgb, frame, xlim, ylim, xs, ys, colour, exclude, others)
    width = frame[2] - frame[0]
    span = (min(xs[-1], xlim[1]) - max(xs[0], xlim[0])) / (xlim[1] - xlim[0])
    assert compared >= least * width * span - 4, f"{what}: only {compared} pixel columns compared"
    assert not bad, f"{what}: {len(bad)} of {compared} pixel columns differ from the CSV, e.g.\n  " + "\n  ".join(bad[:8])


def assert_differs(rgb, frame, xlim, ylim, xs, ys, colour, exclude=None, others=()):
    """The same check against the wrong values must fail on many columns."""
    compared, bad = line_mismatches(rgb, frame, xlim, ylim, xs, ys, colour, exclude, others)
    assert compared > 50 and len(bad) > 0.2 * compared, \
        f"the check passes for the wrong column too ({len(bad)} of {compared} differ)"


# ---- a PNG that has its axes and its line, drawing the CSV's values

def test_the_png_has_its_size_axes_and_a_line_of_the_csv_values():
    x = np.linspace(0.0, 2.0, 201)
    write_csv("square.csv", ["depth [m]", "force [N]", "other [N]"], zip(x, x ** 2, 4 - x ** 2))
    # limits that keep the curve off the frame (a line under a spine is hidden by it)
    p = run_ok("square.csv", "--x", "depth", "--y", "force", "--xlim", "-0.1,2.1", "--ylim", "-0.5,4.5",
               "--output", "square.png", "--report")
    report = json.loads(p.stdout)
    assert png_size("square.png") == (800, 500)
    assert (report["width"], report["height"]) == (800, 500)
    rgb = pixels("square.png")
    assert rgb.shape == (500, 800, 3)

    # the axes: a left and a bottom black line over most of the plot, where the report says
    frame = frame_of(rgb, report)
    left, top, right, bottom = axes_frame(rgb)  # the spines' pixels
    assert right - left > 0.75 * 800 and bottom - top > 0.7 * 500, f"a small plot area: {frame}"
    black = rgb.max(axis=2) < 0.35
    assert black[int(top):int(bottom), int(left)].mean() > 0.95, "the left axis line is broken"
    assert black[int(bottom), int(left):int(right)].mean() > 0.95, "the bottom axis line is broken"
    # tick labels and axis labels: black text left of the left axis and below the bottom one
    assert black[int(top):int(bottom), :int(left) - 2].sum() > 200
    assert black[int(bottom) + 2:, int(left):int(right)].sum() > 200

    # the line: its colour, inside the frame only, and the values it draws are the CSV's
    assert report["lines"] == [{"column": "force [N]", "label": "force [N]", "color": "#1f77b4",
                                "points": 201, "scale": 1.0}]
    blue = of_colour(rgb, BLUE)
    assert blue[int(top) + 1:int(bottom), int(left) + 1:int(right)].sum() > 1000
    assert blue.sum() == blue[int(top) - 1:int(bottom) + 2, int(left) - 1:int(right) + 2].sum(), \
        "pixels of the line's colour outside the axes"
    assert report["xlim"] == [-0.1, 2.1] and report["ylim"] == [-0.5, 4.5]
    data = read_csv("square.csv")
    lim = ((-0.1, 2.1), (-0.5, 4.5))
    assert_draws(rgb, frame, *lim, data["depth"], data["force"], BLUE, what="force against depth")
    assert_differs(rgb, frame, *lim, data["depth"], data["other"], BLUE)
    assert (report["xlabel"], report["ylabel"], report["title"]) == ("depth [m]", "force [N]", "square.csv")


def test_a_monitor_csv_is_drawn_as_it_is_with_automatic_limits():
    data = read_csv(PALPATION)
    report = json.loads(run_ok(PALPATION, "--y", "probe_force_z", "--output", "force.png", "--report").stdout)
    rgb = pixels("force.png")
    frame = frame_of(rgb, report)
    xlim, ylim = report["xlim"], report["ylim"]
    # automatic limits hold every value, with matplotlib's margins
    assert xlim[0] < data["time"].min() and xlim[1] > data["time"].max()
    assert ylim[0] < data["probe_force_z"].min() and ylim[1] > data["probe_force_z"].max()
    assert_draws(rgb, frame, xlim, ylim, data["time"], data["probe_force_z"], BLUE, what="probe_force_z")
    assert_differs(rgb, frame, xlim, ylim, data["time"], data["probe_force_x"], BLUE)
    assert (report["xlabel"], report["ylabel"]) == ("time [s]", "probe_force_z [N]")


def test_several_columns_are_several_lines_with_a_legend():
    data = read_csv(PALPATION)
    t = data["time"]
    fx, ty, fz = data["probe_force_x"], data["probe_torque_y"], data["probe_force_z"]
    p = run_ok(PALPATION, "--y", "probe_force_x", "--y", "probe_torque_y,probe_force_z", "--xlim", "0,1.2",
               "--ylim", "-1.5,3.6", "--output", "three.png", "--report")
    report = json.loads(p.stdout)
    assert [ln["column"] for ln in report["lines"]] == ["probe_force_x [N]", "probe_torque_y [N m]", "probe_force_z [N]"]
    assert [ln["color"] for ln in report["lines"]] == ["#1f77b4", "#ff7f0e", "#2ca02c"]
    assert report["ylabel"] == "probe_force_x [N], probe_torque_y [N m], probe_force_z [N]"
    legend = report["legend_px"]
    assert legend is not None
    rgb = pixels("three.png")
    frame = frame_of(rgb, report)
    green = (0x2c, 0xa0, 0x2c)
    # the legend shows each line's colour
    inside = rgb[int(legend["top"]):int(legend["bottom"]), int(legend["left"]):int(legend["right"])]
    for colour in (BLUE, ORANGE, green):
        assert of_colour(inside, colour).sum() > 20, f"no sample of {colour} in the legend"
    # each line draws its own column (where no later line is drawn over it), not another's
    lim = ((0, 1.2), (-1.5, 3.6))
    assert_draws(rgb, frame, *lim, t, fz, green, legend, least=0.8, what="probe_force_z")
    assert_draws(rgb, frame, *lim, t, ty, ORANGE, legend, others=[(t, fz)], least=0.2, what="probe_torque_y")
    assert_draws(rgb, frame, *lim, t, fx, BLUE, legend, others=[(t, ty), (t, fz)], least=0.2, what="probe_force_x")
    assert_differs(rgb, frame, *lim, t, fx, green, legend)
    assert_differs(rgb, frame, *lim, t, fz, BLUE, legend, others=[(t, ty)])


def test_scale_factors_change_the_values_drawn_and_the_units():
    data = read_csv(PALPATION)
    p = run_ok(PALPATION, "--y", "probe_force_z", "--scale-x", "1000:ms", "--scale-y", "1000:mN",
               "--xlim", "0,1200", "--ylim", "-500,3500", "--output", "scaled.png", "--report",
               "--title", "palpation", "--size", "640x400")
    report = json.loads(p.stdout)
    assert png_size("scaled.png") == (640, 400)
    assert (report["xlabel"], report["ylabel"], report["title"]) == ("time [ms]", "probe_force_z [mN]", "palpation")
    rgb = pixels("scaled.png")
    frame = frame_of(rgb, report)
    assert_draws(rgb, frame, (0, 1200), (-500, 3500), data["time"] * 1000, data["probe_force_z"] * 1000, BLUE,
                 what="the scaled probe_force_z")
    assert_differs(rgb, frame, (0, 1200), (-500, 3500), data["time"] * 1000, data["probe_force_z"], BLUE)


def test_an_offset_turns_a_height_into_a_depth():
    z = np.linspace(0.068, 0.060, 21)  # a probe going down 8 mm, pushing back linearly past 0.063
    f = np.maximum(0.0, 0.063 - z) * 600
    write_csv("press.csv", ["time [s]", "probe_z [m]", "probe_force_z [N]"], zip(np.linspace(0, 1, 21), z, f))
    p = run_ok("press.csv", "--x", "probe_z", "--y", "probe_force_z", "--scale-x", "-1000:mm", "--offset-x", "65",
               "--xlim", "-4,6", "--ylim", "-0.5,2", "--output", "depth.png", "--report", "--title", "")
    report = json.loads(p.stdout)
    assert report["x"] == {"column": "probe_z [m]", "scale": -1000.0, "offset": 65.0}
    assert report["xlabel"] == "-probe_z [mm] + 65"
    rgb = pixels("depth.png")
    frame = frame_of(rgb, report)
    depth = 65 - 1000 * z
    assert_draws(rgb, frame, (-4, 6), (-0.5, 2), depth, f, BLUE, what="force against depth")
    assert_differs(rgb, frame, (-4, 6), (-0.5, 2), depth - 1.5, f, BLUE)  # another offset


def test_the_defaults_time_along_x_every_other_column_and_the_csv_name():
    x = np.linspace(0, 1, 11)
    write_csv("curve.csv", ["u0_z [m]", "time [s]", "u1_z [m]"], zip(-x, x, -2 * x))
    report = json.loads(run_ok("curve.csv", "--report").stdout)
    assert report["png"] == "curve.png"
    assert png_size("curve.png") == (800, 500)
    assert report["x"]["column"] == "time [s]"
    assert [ln["column"] for ln in report["lines"]] == ["u0_z [m]", "u1_z [m]"]
    assert (report["xlabel"], report["ylabel"], report["title"]) == ("time [s]", "u0_z, u1_z [m]", "curve.csv")
    assert sorted(os.listdir(".")) == ["curve.csv", "curve.png"]


def test_help_prints_the_usage():
    p = run("--help")
    assert p.returncode == 0 and p.stderr == ""
    assert p.stdout.splitlines()[0] == "fascia-plot: plot a Monitor's CSV columns as a PNG"
    assert "exit codes:" in p.stdout


# ---- bad input: one line on stderr, its exit code, nothing written

GOOD = "time [s],reaction_z [N]\n0,0\n0.1,1.5\n0.2,2.5\n"

BAD = [
    # name, files {name: text or bytes, or "dir"}, arguments, exit code, the exact line on stderr
    ("missing_file", {}, ["nowhere.csv"], 2, "nowhere.csv: error: cannot open 'nowhere.csv': no such file"),
    ("folder", {"data.csv": "dir"}, ["data.csv"], 2, "data.csv: error: 'data.csv' is a folder, not a CSV file"),
    ("empty", {"e.csv": ""}, ["e.csv"], 2, "e.csv: error: the file is empty: no header line, no rows"),
    ("blank_lines_only", {"e.csv": "\n\n  \n"}, ["e.csv"], 2, "e.csv: error: the file is empty: no header line, no rows"),
    ("header_only", {"h.csv": "time [s],reaction_z [N]\n"}, ["h.csv"], 2,
     "h.csv: error: no rows after the header (line 1): nothing to plot"),
    ("no_header", {"n.csv": "0,1\n1,2\n"}, ["n.csv"], 2,
     "n.csv:1: error: the first line holds numbers, not column names: a Monitor's CSV starts with its header (time [s],...)"),
    ("not_text", {"b.csv": b"time [s],f [N]\n0,\xff\n"}, ["b.csv"], 2,
     "b.csv: byte 17: error: not UTF-8 text: a Monitor's CSV is text"),
    ("unknown_column", {"m.csv": GOOD}, ["m.csv", "--y", "reaction_q"], 2,
     "m.csv:1: error: no column 'reaction_q' (did you mean 'reaction_z'?); the columns are: time, reaction_z"),
    ("unknown_x_column", {"m.csv": GOOD}, ["m.csv", "--x", "depth"], 2,
     "m.csv:1: error: no column 'depth'; the columns are: time, reaction_z"),
    ("not_a_number", {"m.csv": GOOD.replace("1.5", "1.5N")}, ["m.csv"], 2,
     "m.csv:3: error: column 2 'reaction_z': '1.5N' is not a number"),
    ("empty_value", {"m.csv": GOOD.replace("0.2,", ",")}, ["m.csv"], 2,
     "m.csv:4: error: column 1 'time': an empty value"),
    ("too_few_values", {"m.csv": GOOD + "0.3\n"}, ["m.csv"], 2,
     "m.csv:5: error: 1 value, but the header (line 1) names 2 columns"),
    ("no_finite_value", {"m.csv": "time [s],residual [N]\n0,nan\n0.1,-nan\n"}, ["m.csv"], 2,
     "m.csv: error: column 2 'residual' holds no finite value (nan or inf on every row): nothing to plot"),
    ("only_one_column", {"t.csv": "time [s]\n0\n1\n"}, ["t.csv"], 2,
     "t.csv:1: error: the only column is 'time': nothing to plot against it"),
    ("ambiguous_column", {"m.csv": "time [s],f [N],f [mN]\n0,1,2\n"}, ["m.csv", "--y", "f"], 2,
     "m.csv:1: error: column 'f' is ambiguous: columns 2 and 3 have that name; give it with its unit"),
    ("ambiguous_column_control", {"m.csv": "time [s],f [N],f [mN]\n0,1,2\n"}, ["m.csv", "--y", "f [mN]", "--x", "nope"], 2,
     "m.csv:1: error: no column 'nope'; the columns are: time, f, f"),
    # outputs that cannot be written: exit 1
    ("output_folder_missing", {"m.csv": GOOD}, ["m.csv", "--output", "nowhere/plot.png"], 1,
     "nowhere/plot.png: error: cannot write 'nowhere/plot.png': no folder 'nowhere'"),
    ("output_is_folder", {"m.csv": GOOD, "plot.png": "dir"}, ["m.csv", "--output", "plot.png"], 1,
     "plot.png: error: cannot write 'plot.png': it is a folder"),
    ("output_under_file", {"m.csv": GOOD, "taken": "file"}, ["m.csv", "--output", "taken/plot.png"], 1,
     "taken/plot.png: error: cannot write 'taken/plot.png': 'taken' is a file, not a folder"),
    ("output_is_fifo", {"m.csv": GOOD, "pipe.png": "fifo"}, ["m.csv", "--output", "pipe.png"], 1,
     "pipe.png: error: cannot write 'pipe.png': it exists and is not a regular file"),
    # the command line: exit 1, as fascia-run's
    ("no_csv", {}, ["--y", "a"], 1, "fascia-plot: no CSV file given (fascia-plot --help shows the usage)"),
    ("two_csvs", {}, ["a.csv", "b.csv"], 1, "fascia-plot: one CSV file at a time ('a.csv' and 'b.csv')"),
    ("unknown_option", {"m.csv": GOOD}, ["m.csv", "--colour", "red"], 1, "fascia-plot: unknown option '--colour'"),
    ("unknown_short_option", {"m.csv": GOOD}, ["m.csv", "-x", "time"], 1, "fascia-plot: unknown option '-x'"),
    ("option_without_value", {"m.csv": GOOD}, ["m.csv", "--x"], 1, "fascia-plot: --x needs a value"),
    ("option_before_option", {"m.csv": GOOD}, ["m.csv", "--y", "--report"], 1, "fascia-plot: --y needs a value"),
    ("empty_column_in_list", {"m.csv": GOOD}, ["m.csv", "--y", "a,,b"], 1,
     "fascia-plot: --y needs column names separated by commas, not 'a,,b'"),
    ("output_not_png", {"m.csv": GOOD}, ["m.csv", "--output", "plot.svg"], 1,
     "fascia-plot: --output writes a PNG: give a name ending in .png, not 'plot.svg'"),
    ("scale_zero", {"m.csv": GOOD}, ["m.csv", "--scale-y", "0"], 1,
     "fascia-plot: --scale-y needs a finite, non-zero factor with an optional unit (e.g. 1000:mm), not '0'"),
    ("scale_not_number", {"m.csv": GOOD}, ["m.csv", "--scale-x", "k:mm"], 1,
     "fascia-plot: --scale-x needs a finite, non-zero factor with an optional unit (e.g. 1000:mm), not 'k:mm'"),
    ("offset_not_finite", {"m.csv": GOOD}, ["m.csv", "--offset-x", "inf"], 1,
     "fascia-plot: --offset-x needs a finite number, not 'inf'"),
    ("limits_reversed", {"m.csv": GOOD}, ["m.csv", "--xlim", "2,1"], 1, "fascia-plot: --xlim needs MIN < MAX, not '2,1'"),
    ("limits_one_number", {"m.csv": GOOD}, ["m.csv", "--ylim", "3"], 1,
     "fascia-plot: --ylim needs MIN,MAX (either may be empty), not '3'"),
    ("size_malformed", {"m.csv": GOOD}, ["m.csv", "--size", "800"], 1,
     "fascia-plot: --size needs WxH in pixels, each in [100, 8000], such as 800x500, not '800'"),
    ("flag_with_value", {"m.csv": GOOD}, ["m.csv", "--report=yes"], 1, "fascia-plot: --report takes no value"),
]


def listing(folder="."):
    out = {}
    for root, dirs, files in os.walk(folder):
        for name in dirs + files:
            p = os.path.join(root, name)
            st = os.lstat(p)
            out[p] = (stat.S_IFMT(st.st_mode), st.st_size, st.st_mtime_ns)
    return out


@pytest.mark.parametrize("name,files,args,code,message", BAD, ids=[b[0] for b in BAD])
def test_bad_input_is_one_line_and_an_exit_code(name, files, args, code, message):
    for path, text in files.items():
        if text == "dir":
            os.mkdir(path)
        elif text == "fifo":
            os.mkfifo(path)
        elif text == "file":
            open(path, "w").write("a file\n")
        else:
            open(path, "wb").write(text if isinstance(text, bytes) else text.encode())
    before = listing()
    p = run(*args)
    assert (p.returncode, p.stderr) == (code, message + "\n"), p.stderr
    assert p.stdout == ""
    assert listing() == before, "the run left the folder changed"


def test_a_failed_write_leaves_the_older_png_and_no_temporary_file():
    open("m.csv", "w").write(GOOD)
    os.mkdir("mpl")
    # matplotlib's font cache in a folder of the test's, written by this first run, so that the second
    # run writes nothing but its PNG
    env = {"MPLCONFIGDIR": os.path.abspath("mpl")}
    p = run_ok("m.csv", "--output", "plot.png", env=env)
    assert p.stdout == "fascia-plot: wrote plot.png (800 x 500 px, 1 line, 3 rows)\n"
    assert png_size("plot.png") == (800, 500)
    older = open("plot.png", "rb").read()
    # a file size limit of 4 KiB: the new PNG (some 20 KiB) fails while it is being written
    p = run("m.csv", "--output", "plot.png", "--title", "another", limit_file_size=4096, env=env)
    assert (p.returncode, p.stderr, p.stdout) == (1, "plot.png: error: cannot write 'plot.png': File too large\n", "")
    assert open("plot.png", "rb").read() == older
    assert sorted(os.listdir(".")) == ["m.csv", "mpl", "plot.png"], "a temporary file was left behind"


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into a folder without write permission")
def test_an_output_folder_without_permission_is_an_output_error():
    open("m.csv", "w").write(GOOD)
    os.mkdir("ro")
    os.chmod("ro", 0o555)
    try:
        p = run("m.csv", "--output", "ro/plot.png")
        assert (p.returncode, p.stderr) == (1, "ro/plot.png: error: cannot write 'ro/plot.png': no permission to write into 'ro'\n")
        assert os.listdir("ro") == []
    finally:
        os.chmod("ro", 0o755)
