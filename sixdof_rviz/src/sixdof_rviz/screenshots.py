"""Screenshots of an X display (rviz under xvfb) as numpy images, and masks of the colours sixdof's rviz displays
draw: what the rviz tests of sixdof_rviz and sixdof_tests look for on screen. Needs imagemagick's `import`."""

from __future__ import annotations

import subprocess
import time

import numpy as np

# Tries of `import`, which fails now and then while a window redraws.
IMPORT_TRIES = 3


def decode_ppm(ppm: bytes) -> np.ndarray:
    """A binary PPM ("P6\\n<w> <h>\\n<max>\\n" then the pixels, 8 bits) as an HxWx3 uint8 array."""
    header = ppm.split(b"\n", 3)
    if len(header) < 4 or header[0] != b"P6":
        raise ValueError("not a binary PPM image")
    width, height = (int(v) for v in header[1].split())
    return np.frombuffer(header[3], dtype=np.uint8, count=width * height * 3).reshape(height, width, 3)


def screenshot(window: str = "root", save_as: str | None = None) -> np.ndarray:
    """The X window `window` (an id, or 'root': the whole display) as an HxWx3 uint8 array; also written to
    `save_as` (e.g. a PNG for a person to look at) when given. RuntimeError naming the window if `import` fails
    IMPORT_TRIES times."""
    for attempt in range(IMPORT_TRIES):
        shot = subprocess.run(["import", "-window", window, "-depth", "8", "ppm:-"], capture_output=True)
        if shot.returncode == 0:
            break
        if attempt == IMPORT_TRIES - 1:
            raise RuntimeError(f"no screenshot of window {window}: {shot.stderr.decode().strip()}")
        time.sleep(1.0)  # the window is being redrawn: the next try comes after it
    if save_as:
        subprocess.run(["convert", "ppm:-", save_as], input=shot.stdout, check=True)
    return decode_ppm(shot.stdout)


def settled_screenshot(
    window: str = "root", save_as: str | None = None, timeout: float = 60.0, changed_pixels: int = 100
) -> np.ndarray:
    """A screenshot once the drawing is still: two shots in a row differ in fewer than `changed_pixels` pixels
    (rviz has drawn what it was given). RuntimeError if it is not still within `timeout` s (wall clock)."""
    deadline = time.monotonic() + timeout
    previous = screenshot(window)
    while True:
        image = screenshot(window, save_as)
        if int(np.any(image != previous, axis=2).sum()) < changed_pixels:
            return image
        if time.monotonic() > deadline:
            raise RuntimeError(f"the drawing of window {window} did not settle within {timeout:g} s")
        previous = image


def channels(image: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The red, green and blue channels of an HxWx3 image as int arrays (room for sums and products)."""
    return tuple(image[:, :, i].astype(int) for i in range(3))


def marker_sphere_mask(image: np.ndarray) -> np.ndarray:
    """The Goal State marker's yellow drag sphere (0.9, 0.9, 0.2), under any shading."""
    r, g, b = channels(image)
    return (r > 150) & (g * 4 > r * 3) & (b * 2 < g)
