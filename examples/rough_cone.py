"""A notebook-style tour of indentmap from Python: a rough surface, its statistics, a cone pressed into
it, the contact area against the paper's eq. (12), and pictures. Run it as a script or cell by cell:

    PYTHONPATH=build/python /usr/bin/python3 examples/rough_cone.py [OUTPUT_FOLDER]
"""
import os
import sys

import numpy as np

import indentmap as im

out = sys.argv[1] if len(sys.argv) > 1 else "output/python_example"
os.makedirs(out, exist_ok=True)

# %% A self-affine surface like the paper's (H = 0.8, lambda_s = 4 delta), smaller and rougher.
heights = im.generate(256, hurst=0.8, slope=0.16, seed=7)
stats = im.statistics(heights)
print(f"h_rms = {stats['height_rms']:.3f} delta, h'rms = {stats['slope_rms_spectral']:.3f} (spectral), "
      f"{stats['slope_rms_fd']:.3f} (forward differences), Nayak {stats['nayak']:.1f}")
q, c, counts = im.psd(heights, bins=32, counts=True)
# the self-affine range below q_s = 2 pi / lambda_s (no power above), in shells of at least 8 wavevectors
# (the few in the lowest shells scatter; an empty shell's C is NaN)
fitted = (q < 2 * np.pi / 4.0) & (counts >= 8)
slope_fit = np.polyfit(np.log(q[fitted]), np.log(c[fitted]), 1)[0]
print(f"PSD exponent {slope_fit:.2f} (self-affine: -2(1 + H) = -3.6)")

# %% An 80 degree cone, load control: ten loads up to N* = 3000.
cone = im.Cone(80.0)
cot = 1.0 / np.tan(np.radians(80.0))
loads = np.linspace(300, 3000, 10) * cot / 2.0         # N = N* E* cot(alpha) delta^2 / 2
history, fields = im.indent(heights, cone, loads=loads, fields=True, tol=1e-6)
theory = im.theory.area_ratio(stats["slope_rms_spectral"], alpha=80.0)
print("N*      A/A_cone  eq. (12)")
for row in history:
    print(f"{row['load_star']:7.0f} {row['area_ratio']:9.3f} {theory:9.3f}")

# %% Pictures: the last contact map with the smooth circle, the deformed surface, a two-panel figure.
force = fields[-1]["force"]
radius = np.sqrt(history["load_star"][-1] / np.pi)      # the smooth cone's contact radius in delta
im.contact_map(force, colormap="magma", log=True, circle_radius=radius).save(os.path.join(out, "contact.png"))
deformed = heights - fields[-1]["displacement"]
im.height_map(deformed, contact=force).save(os.path.join(out, "deformed.png"))
im.Figure([fields[2]["force"], force], columns=2, labels=["(a)", "(b)"],
          titles=[f"N* = {history['load_star'][2]:.0f}", f"N* = {history['load_star'][-1]:.0f}"],
          colormap="magma", log=True, circle_radius=radius).save(os.path.join(out, "panels.pdf"))
print(f"pictures written under {out}")
