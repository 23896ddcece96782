"""Draw the pictures of the README's gallery: one PNG per built-in scene and one animation.

    PYTHONPATH=src python docs/gallery/make_gallery.py

The same pictures come from the command line (``quadric-contact simulate SCENE
--plot SCENE.png``, ``--animate SCENE.gif``); this script only makes them small.
"""

from __future__ import annotations

import io
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "src"))

from quadric_contact.exact.optional import pyplot  # noqa: E402
from quadric_contact.interfaces.animation import render_gif  # noqa: E402
from quadric_contact.interfaces.plotting import plot_result  # noqa: E402
from quadric_contact.scenes.scene_toml import builtin_scene, builtin_scene_names  # noqa: E402
from quadric_contact.scenes.simulate import simulate  # noqa: E402


def main() -> None:
    plt = pyplot()
    for name in builtin_scene_names():
        result = simulate(builtin_scene(name))
        fig = plot_result(result, max_pairs=3, samples=160)
        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=55, bbox_inches="tight")
        plt.close(fig)
        (HERE / f"{name}.png").write_bytes(buf.getvalue())
        print(f"{name}.png")
    for name in ("trough_and_channel", "bees_meeting"):
        gif = render_gif(simulate(builtin_scene(name)), frames=20, fps=5, dpi=55)
        (HERE / f"{name}.gif").write_bytes(gif)
        print(f"{name}.gif")


if __name__ == "__main__":
    main()
