"""`sward new FILE --scene NAME --species-map IMAGE` (Papavasiliou §3.3): the grass types grow
where the image is nearest their blades' colour, none where it is nearest the soil's."""

import numpy as np
from PIL import Image

from app.scenes import get_scene
from core.patch import generate_patch
from core.project_file import load_project
from tests.test_cli import sward


def test_a_colour_map_places_each_type_where_its_colour_is(tmp_path):
    document = get_scene("meadow").document()
    main, tall = (
        generate_patch(k.params).vertices["color"].mean(axis=0) for k in document.grass_types
    )
    w, h = document.maps.size
    image = np.zeros((h, w, 3))
    third = w // 3
    image[:, :third], image[:, third : 2 * third] = main, tall
    image[:, 2 * third :] = document.light.soil_color
    Image.fromarray(np.round(image * 255).astype(np.uint8)).save(tmp_path / "colours.png")
    project = tmp_path / "placed.sward"
    r = sward(
        "new", str(project), "--scene", "meadow", "--species-map", str(tmp_path / "colours.png")
    )
    assert r.returncode == 0, r.stderr
    density = load_project(project).maps.layer("density")
    kinds = document.grass_types
    a, b = density[..., kinds[0].channel], density[..., kinds[1].channel]
    margin = 4  # texels away from the bands' borders
    left, middle = (
        (slice(None), slice(margin, third - margin)),
        (slice(None), slice(third + margin, 2 * third - margin)),
    )
    right = (slice(None), slice(2 * third + margin, w - margin))
    assert a[left].sum() >= 0.9 * (a[left] + b[left]).sum() and a[left].mean() > 0.9
    assert b[middle].sum() >= 0.9 * (a[middle] + b[middle]).sum() and b[middle].mean() > 0.9
    assert (a[right] + b[right]).max() < 0.05  # the soil's colour: bare


def test_a_species_map_that_is_no_image_is_refused_naming_it(tmp_path):
    bad = tmp_path / "colours.png"
    bad.write_text("not an image")
    r = sward("new", str(tmp_path / "x.sward"), "--scene", "meadow", "--species-map", str(bad))
    assert r.returncode == 2 and "--species-map: colours.png" in r.stderr
    assert "Traceback" not in r.stderr and not (tmp_path / "x.sward").exists()
