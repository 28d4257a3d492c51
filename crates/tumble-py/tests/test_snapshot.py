"""save/load: a restored world steps bit-identically; damaged data is a clear error."""

import pytest

import tumble


def busy_world() -> tumble.World:
    w = tumble.World(gravity=(0, 0, -9.81))
    w.add_body(tumble.Box((5.0, 5.0, 0.5)), kind="static", position=(0, 0, -0.5))
    for i in range(6):
        w.add_body(tumble.Sphere(0.2), density=500.0, position=(0.1 * i, 0.0, 0.5 + 0.5 * i),
                   angular_velocity=(0.0, 1.0, 0.2 * i))
    return w


def test_load_then_step_is_bit_identical():
    w = busy_world()
    w.step(1 / 60, n=30)
    restored = tumble.World.load(w.save())
    assert restored.state_hash() == w.state_hash()
    for _ in range(120):
        w.step(1 / 60)
        restored.step(1 / 60)
        assert restored.state_hash() == w.state_hash()
    assert (restored.positions == w.positions).all()


def test_damaged_snapshots_raise_value_errors():
    data = busy_world().save()
    with pytest.raises(ValueError, match="truncated"):
        tumble.World.load(data[: len(data) // 2])
    with pytest.raises(tumble.TumbleError, match="not a Tumble snapshot"):
        tumble.World.load(b"not a snapshot at all")
    damaged = bytearray(data)
    damaged[len(damaged) // 2] ^= 0x40
    with pytest.raises(ValueError, match="damaged"):
        tumble.World.load(bytes(damaged))
