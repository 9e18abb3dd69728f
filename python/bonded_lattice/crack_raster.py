"""Crack networks drawn as rasters: legible pictures of tens of thousands of broken bonds.

A broken bond is drawn as a crack segment of length d across the bond at its midpoint
(:func:`crack_segments`, the segment of the dual lattice that the bond crosses).  Drawn as
vector lines (matplotlib's ``LineCollection``) every segment is stroked at the line width,
about 2 pixels: at the seed's 737,600 particles a lattice spacing is under one pixel of
the figure, so neighbouring cracks merge and the file carries every segment.  Here the
segments are instead accumulated into a pixel grid of the axes' own resolution
(:class:`PixelGrid`, :func:`segment_pixels`): a pixel lights where a crack segment passes,
with the number of segments that touch it (:func:`count_raster`) or the earliest strain
step among them (:func:`first_value_raster`); the grains or the layer are a faint
background raster of the nearest particle's grain, their boundaries a grey line
(:func:`nearest_particle_raster`, :func:`boundary_mask`).  :func:`draw_scene_raster` puts
it on a figure's axes; :func:`choose_method` picks vector segments or the raster by the
number of broken bonds (:data:`SEGMENT_LIMIT`, measured by ``bench/crack_pictures.py``,
docs/scenes.md "Pictures").
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

# above this many broken bonds a scene picture is drawn as a raster (bench/crack_pictures.py,
# docs/scenes.md "Pictures": from 1e4 on the segments' PNG is 2.5-4 times the raster's, at
# 2e5 they also take 1.8 times its CPU time; the raster keeps cracks 3 d apart separate at
# the seed's high resolution, where 2-pixel segment strokes merge them; below 1e4 the
# segments are the faster, at most 0.5 s)
SEGMENT_LIMIT = 10000

METHODS = ("auto", "segments", "raster")

TENSION_RGB = (0.0, 0.0, 0.0)
SHEAR_RGB = (0.84, 0.15, 0.16)       # matplotlib's tab:red
BOUNDARY_RGB = (0.6, 0.6, 0.6)
HIGHLIGHT_RGB = (0.62, 0.79, 0.88)   # #9ecae1, the growing grains
TINT = 0.12                          # weight of a grain's colour in its faint background


@dataclass(frozen=True)
class PixelGrid:
    """nx x ny pixels covering [x0, x1] x [y0, y1]; pixel (iy, ix) covers
    [x0 + ix px, x0 + (ix + 1) px) x [y0 + iy py, y0 + (iy + 1) py), row 0 at the bottom
    (``imshow(origin="lower")``)."""

    x0: float
    x1: float
    y0: float
    y1: float
    nx: int
    ny: int

    def __post_init__(self) -> None:
        if self.nx < 1 or self.ny < 1:
            raise ValueError(f"a pixel grid of {self.nx} x {self.ny} pixels is out of range: "
                             "need at least 1 x 1")
        if not (self.x1 > self.x0 and self.y1 > self.y0):
            raise ValueError(f"pixel grid extent [{self.x0}, {self.x1}] x [{self.y0}, {self.y1}] "
                             "is empty: need x1 > x0 and y1 > y0")

    @property
    def px(self) -> float:
        """Pixel width (data units)."""
        return (self.x1 - self.x0) / self.nx

    @property
    def py(self) -> float:
        """Pixel height (data units)."""
        return (self.y1 - self.y0) / self.ny

    @property
    def extent(self) -> tuple[float, float, float, float]:
        """(x0, x1, y0, y1), for ``imshow(extent=...)``."""
        return (self.x0, self.x1, self.y0, self.y1)

    def flat_index(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """Flat pixel index iy nx + ix of points (x, y); -1 for points outside the grid."""
        ix = np.floor((np.asarray(x, dtype=float) - self.x0) / self.px).astype(np.int64)
        iy = np.floor((np.asarray(y, dtype=float) - self.y0) / self.py).astype(np.int64)
        inside = (ix >= 0) & (ix < self.nx) & (iy >= 0) & (iy < self.ny)
        return np.where(inside, iy * self.nx + ix, -1)

    def centres(self) -> tuple[np.ndarray, np.ndarray]:
        """x and y of the pixel centres, each (ny, nx)."""
        x = self.x0 + (np.arange(self.nx) + 0.5) * self.px
        y = self.y0 + (np.arange(self.ny) + 0.5) * self.py
        return np.meshgrid(x, y)


def crack_segments(positions: np.ndarray, i: np.ndarray, j: np.ndarray,
                   length: float, period: np.ndarray | None = None) -> np.ndarray:
    """(m, 2, 2) crack segments: of ``length`` (the diameter d), across each bond (i, j)
    (0-based particle indices) at its midpoint, normal to it; with ``period`` (the (x, y)
    lengths of a periodic box) a bond across the seam is taken at its minimum image, its
    midpoint beside particle i."""
    if not length > 0:
        raise ValueError(f"crack segment length = {length} is out of range: need > 0")
    p = np.asarray(positions, dtype=float)[:, :2]
    i, j = np.asarray(i, dtype=np.int64), np.asarray(j, dtype=np.int64)
    sep = p[j] - p[i]
    if period is not None:
        box = np.asarray(period, dtype=float)
        sep -= box * np.round(sep / box)
    u = sep / np.linalg.norm(sep, axis=1, keepdims=True)
    normal = np.stack([-u[:, 1], u[:, 0]], axis=1) * 0.5 * length
    mid = p[i] + 0.5 * sep
    return np.stack([mid - normal, mid + normal], axis=1)


def segment_pixels(segments: np.ndarray, grid: PixelGrid) -> tuple[np.ndarray, np.ndarray]:
    """The pixels each segment passes through: (segment index, flat pixel index) pairs,
    each pair once, sorted by segment.

    A segment is sampled at both ends and at equal intervals of at most half the smaller
    pixel side; a pixel is lit if a sample falls in it.  A corner that a segment clips by
    less than half a pixel side can be missed; a segment is never drawn into a pixel it
    does not touch.  Samples outside the grid are dropped.
    """
    seg = np.asarray(segments, dtype=float).reshape(-1, 2, 2)
    if len(seg) == 0:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    longest = float(np.linalg.norm(seg[:, 1] - seg[:, 0], axis=1).max())
    samples = int(math.ceil(2.0 * longest / min(grid.px, grid.py))) + 1
    t = np.linspace(0.0, 1.0, max(samples, 2))
    x = seg[:, 0, 0, None] + t[None, :] * (seg[:, 1, 0] - seg[:, 0, 0])[:, None]
    y = seg[:, 0, 1, None] + t[None, :] * (seg[:, 1, 1] - seg[:, 0, 1])[:, None]
    flat = grid.flat_index(x, y)
    owner = np.broadcast_to(np.arange(len(seg))[:, None], flat.shape)
    keep = flat >= 0
    pairs = np.unique(owner[keep] * (grid.nx * grid.ny) + flat[keep])
    return pairs // (grid.nx * grid.ny), pairs % (grid.nx * grid.ny)


def count_raster(segments: np.ndarray, grid: PixelGrid) -> np.ndarray:
    """(ny, nx) number of segments that pass through each pixel (:func:`segment_pixels`)."""
    _, flat = segment_pixels(segments, grid)
    return np.bincount(flat, minlength=grid.nx * grid.ny).reshape(grid.ny, grid.nx)


def first_value_raster(segments: np.ndarray, values: np.ndarray, grid: PixelGrid) -> np.ndarray:
    """(ny, nx) smallest value (e.g. the strain step of the break) among the segments that
    pass through each pixel; NaN where none does."""
    values = np.asarray(values, dtype=float)
    if len(values) != len(np.asarray(segments).reshape(-1, 2, 2)):
        raise ValueError(f"{len(values)} values for {len(segments)} segments: need one each")
    owner, flat = segment_pixels(segments, grid)
    image = np.full(grid.nx * grid.ny, np.inf)
    np.minimum.at(image, flat, values[owner])
    image[np.isinf(image)] = np.nan
    return image.reshape(grid.ny, grid.nx)


def nearest_particle_raster(positions: np.ndarray, grid: PixelGrid, reach: float) -> np.ndarray:
    """(ny, nx) index of the particle nearest each pixel centre; -1 where none lies within
    ``reach`` (outside the lattice).  Equally near particles: the lower index.

    Each particle visits the pixels of the square of half-side ``reach`` around it, so the
    work is the number of particles times (2 reach / pixel + 1)^2: about 2.6 times the pixels
    the lattice covers when reach is 0.75 diameters.
    """
    if not reach > 0:
        raise ValueError(f"reach = {reach} is out of range: need > 0")
    p = np.asarray(positions, dtype=float)[:, :2]
    rx, ry = int(math.ceil(reach / grid.px)), int(math.ceil(reach / grid.py))
    ox, oy = np.meshgrid(np.arange(-rx, rx + 1), np.arange(-ry, ry + 1))
    cx = np.floor((p[:, 0] - grid.x0) / grid.px).astype(np.int64)[:, None] + ox.ravel()
    cy = np.floor((p[:, 1] - grid.y0) / grid.py).astype(np.int64)[:, None] + oy.ravel()
    dist = np.hypot(grid.x0 + (cx + 0.5) * grid.px - p[:, 0, None],
                    grid.y0 + (cy + 0.5) * grid.py - p[:, 1, None])
    keep = (dist < reach) & (cx >= 0) & (cx < grid.nx) & (cy >= 0) & (cy < grid.ny)
    owner = np.broadcast_to(np.arange(len(p))[:, None], keep.shape)[keep]
    flat, dist = (cy * grid.nx + cx)[keep], dist[keep]
    order = np.lexsort((owner, dist, flat))          # per pixel: nearest, then lowest index
    flat, owner = flat[order], owner[order]
    first = np.ones(len(flat), dtype=bool)
    first[1:] = flat[1:] != flat[:-1]
    image = np.full(grid.nx * grid.ny, -1, dtype=np.int64)
    image[flat[first]] = owner[first]
    return image.reshape(grid.ny, grid.nx)


def boundary_mask(labels: np.ndarray) -> np.ndarray:
    """Pixels whose right or upper neighbour carries another label (both labels >= 0):
    the grain boundaries of a label raster, one pixel wide."""
    lab = np.asarray(labels)
    mask = np.zeros(lab.shape, dtype=bool)
    right = (lab[:, :-1] != lab[:, 1:]) & (lab[:, :-1] >= 0) & (lab[:, 1:] >= 0)
    up = (lab[:-1, :] != lab[1:, :]) & (lab[:-1, :] >= 0) & (lab[1:, :] >= 0)
    mask[:, :-1] |= right
    mask[:-1, :] |= up
    return mask


def background_rgba(grain: np.ndarray, nearest: np.ndarray,
                    highlight: np.ndarray | None = None) -> np.ndarray:
    """(ny, nx, 4) faint background: each pixel tinted by its nearest particle's grain
    (tab20's colours, its strong ten first, at weight :data:`TINT` on white), grain boundaries grey, the particles
    of ``highlight`` (a boolean per particle) light blue, transparent outside."""
    from matplotlib import colormaps

    grain = np.asarray(grain, dtype=np.int64)
    inside = nearest >= 0
    labels = np.where(inside, grain[np.maximum(nearest, 0)], -1)
    tab20 = np.asarray(colormaps["tab20"].colors)[:, :3]
    palette = np.concatenate([tab20[0::2], tab20[1::2]])   # the strong ten first
    rgb = 1.0 - TINT * (1.0 - palette[np.maximum(labels, 0) % len(palette)])
    if highlight is not None:
        lit = inside & np.asarray(highlight, dtype=bool)[np.maximum(nearest, 0)]
        rgb[lit] = HIGHLIGHT_RGB
    rgb[boundary_mask(labels)] = BOUNDARY_RGB
    return np.concatenate([rgb, inside[..., None].astype(float)], axis=2)


def mode_rgba(tension: np.ndarray, shear: np.ndarray) -> np.ndarray:
    """(ny, nx, 4) crack pixels from the count rasters of the tension and shear breaks:
    black where a tensile crack passes, red where a shear one does (drawn over tension),
    transparent elsewhere."""
    rgba = np.zeros(tension.shape + (4,))
    rgba[tension > 0] = TENSION_RGB + (1.0,)
    rgba[shear > 0] = SHEAR_RGB + (1.0,)
    return rgba


def choose_method(broken: int, method: str = "auto", limit: int = SEGMENT_LIMIT) -> str:
    """"segments" or "raster" for a picture of ``broken`` broken bonds: ``method`` itself
    unless "auto", which draws segments up to ``limit`` bonds and a raster above."""
    if method not in METHODS:
        raise ValueError(f"method = {method!r} is not valid: use one of {', '.join(METHODS)}")
    if broken < 0 or limit < 0:
        raise ValueError(f"broken = {broken}, limit = {limit} out of range: need >= 0")
    if method != "auto":
        return method
    return "segments" if broken <= limit else "raster"


def axes_grid(fig, ax, dpi: float, layouts: int = 2) -> PixelGrid:
    """The pixel grid of ``ax`` as the figure will be saved at ``dpi``: laid out tightly
    (as :func:`bonded_lattice.plotting.save_png` does) and drawn once, so that one raster
    pixel is one pixel of the PNG, over the axes' current limits."""
    fig.set_dpi(dpi)
    for _ in range(2):   # the first layout of a figure moves again by a pixel at the second
        fig.tight_layout()
        fig.canvas.draw()
    box = ax.get_window_extent()
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    return PixelGrid(x0, x1, y0, y1, max(1, int(round(box.width))),
                     max(1, int(round(box.height))))


def draw_scene_raster(fig, ax, positions: np.ndarray, grain: np.ndarray, segments: np.ndarray,
                      shear: np.ndarray, steps: np.ndarray | None = None,
                      highlight: np.ndarray | None = None, reach: float = 1.0,
                      dpi: float = 130, step_label: str = "strain step") -> PixelGrid:
    """Draw a scene's crack network on ``ax`` as rasters at the saved figure's resolution.

    positions: (n, 2+) particle centres in the axes' units; grain: their grain ids;
    segments: (m, 2, 2) crack segments (:func:`crack_segments`); shear: (m,) True for the
    breaks in shear; steps: (m,) the strain step of each break (colours the cracks by the
    earliest step through each pixel, viridis, with a colour bar) or None (colours by mode,
    with a legend); highlight: particles tinted light blue; reach: the distance from a
    particle beyond which the background is left blank (half a diameter or more).
    The axes' limits, aspect and labels must be set before: the grid is measured from the
    laid-out figure.  Returns the grid.
    """
    from matplotlib import colormaps
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize

    shear = np.asarray(shear, dtype=bool)
    if steps is not None:
        steps = np.asarray(steps, dtype=float)
        lo = float(np.nanmin(steps)) if len(steps) else 0.0
        hi = float(np.nanmax(steps)) if len(steps) else 1.0
        norm = Normalize(vmin=lo, vmax=hi if hi > lo else lo + 1.0)
        cmap = colormaps["viridis"]
        fig.colorbar(ScalarMappable(norm=norm, cmap=cmap), ax=ax,
                     label=f"broken by {step_label}", shrink=0.8)
    else:
        ax.plot([], [], "k-", label=f"tension ({int((~shear).sum())})")
        ax.plot([], [], "-", color="tab:red", label=f"shear ({int(shear.sum())})")
        ax.legend(loc="upper right", fontsize=7)
    images = None
    grid = axes_grid(fig, ax, dpi)
    for _ in range(3):
        nearest = nearest_particle_raster(positions, grid, reach)
        back = background_rgba(grain, nearest, highlight)
        if steps is not None:
            first = first_value_raster(segments, steps, grid)
            cracks = cmap(norm(np.nan_to_num(first, nan=norm.vmin)))
            cracks[..., 3] = np.isfinite(first)
        else:
            cracks = mode_rgba(count_raster(segments[~shear], grid),
                               count_raster(segments[shear], grid))
        if images is None:
            kw = {"origin": "lower", "interpolation": "nearest", "extent": grid.extent}
            images = (ax.imshow(back, zorder=0, **kw), ax.imshow(cracks, zorder=2, **kw))
        else:
            for image, data in zip(images, (back, cracks)):
                image.set_data(data)
                image.set_extent(grid.extent)
        ax.set_xlim(grid.x0, grid.x1)
        ax.set_ylim(grid.y0, grid.y1)
        # should the images have moved the layout by a pixel, measure again and redraw
        again = axes_grid(fig, ax, dpi, layouts=1)
        if (again.nx, again.ny) == (grid.nx, grid.ny):
            break
        grid = again
    return grid
