import numpy as np
import tumble


def test_import():
    w = tumble.World()
    b = w.add_body(tumble.Box((0.5, 0.5, 0.5)), position=(0, 0, 1), name="box")
    w.step(1 / 60, n=10)
    assert w.positions.shape == (1, 3)
    assert w.body(b).name == "box"
