"""USD export: the GLB's tree, materials and metadata, accepted by usd-core's validators."""

import numpy as np
import pytest
from render_fixtures import market_scene, scene_of, thing

from scenewright.api import export
from scenewright.core.errors import InputError
from scenewright.core.relations import Relation
from scenewright.core.room import Room
from scenewright.render.export import preview_camera
from scenewright.render.meshes import object_transform
from scenewright.render.usd_export import export_usd

pxr = pytest.importorskip("pxr")
from pxr import Usd, UsdGeom, UsdLux, UsdShade  # noqa: E402


def _market():
    scene = market_scene()
    scene.objects.append(thing("pot_1", (2, 0.8, 0), (0.3, 0.2, 0.3), parent="market_stand_1"))
    scene.relations = [Relation("pot_1", "table_1", "OnTopOf")]
    return scene


@pytest.fixture(scope="module", params=[".usda", ".usdc"])
def stage(request, tmp_path_factory):
    path = tmp_path_factory.mktemp("usd") / f"market{request.param}"
    export(_market(), path)
    return Usd.Stage.Open(str(path))


def test_stage_metadata_says_metres_and_y_up(stage):
    assert UsdGeom.GetStageMetersPerUnit(stage) == 1.0
    assert UsdGeom.GetStageUpAxis(stage) == UsdGeom.Tokens.y
    assert stage.GetDefaultPrim().GetPath() == "/World"


def test_usd_core_validators_report_nothing(stage):
    from pxr import UsdValidation

    validators = UsdValidation.ValidationRegistry().GetOrLoadAllValidators()
    errors = UsdValidation.ValidationContext(validators).Validate(stage)
    assert [error.GetMessage() for error in errors] == []


def test_same_tree_and_world_poses_as_the_glb(stage):
    pot = stage.GetPrimAtPath("/World/market_stand_1/table_1/pot_1")
    assert pot.IsValid() and pot.GetCustomDataByKey("on") == "table_1"
    cache = UsdGeom.XformCache()
    scene = _market()
    for path, object_id in (
        ("/World/market_stand_1/table_1/pot_1", "pot_1"),
        ("/World/house_1", "house_1"),
    ):
        world = np.array(cache.GetLocalToWorldTransform(stage.GetPrimAtPath(path))).T
        assert np.allclose(world, object_transform(scene.object(object_id)), atol=1e-9)
    assert stage.GetPrimAtPath("/World/house_1").GetCustomDataByKey("type") == "house"
    assert stage.GetPrimAtPath("/World/ground").IsValid()


def test_meshes_bind_preview_surfaces_of_their_colour(stage):
    geom = stage.GetPrimAtPath("/World/market_stand_1/sign_1/Geom0")
    mesh = UsdGeom.Mesh(geom)
    assert mesh.GetNormalsInterpolation() == UsdGeom.Tokens.faceVarying
    material, _ = UsdShade.MaterialBindingAPI(geom).ComputeBoundMaterial()
    shader = UsdShade.Shader(material.ComputeSurfaceSource()[0])
    assert shader.GetIdAttr().Get() == "UsdPreviewSurface"
    assert np.allclose(shader.GetInput("diffuseColor").Get(), (0.2, 0.2, 0.9), atol=0.003)


def test_camera_and_sun(stage):
    camera = UsdGeom.Camera(stage.GetPrimAtPath("/World/camera"))
    lens = camera.GetCamera()
    view = preview_camera(_market())
    assert lens.GetFieldOfView(lens.FOVVertical) == pytest.approx(np.degrees(view.yfov), rel=1e-5)
    assert stage.GetPrimAtPath("/World/sun").IsA(UsdLux.DistantLight)


def test_options_and_a_room(tmp_path):
    scene = scene_of([thing("crate_1", (-1.0, 0.0, -1.0))], room=Room.rectangle(4.0, 3.0))
    path = export_usd(scene, tmp_path / "room.usda", camera=False, light=False, cutaway=True)
    stage = Usd.Stage.Open(str(path))
    names = {prim.GetName() for prim in stage.GetPrimAtPath("/World").GetChildren()}
    assert {"crate_1", "floor"} <= names and not names & {"camera", "sun"}
    walls = [name for name in names if name.startswith("wall_")]
    assert 0 < len(walls) < 4  # the walls the preview cuts away are left out
    assert [p.name for p in tmp_path.iterdir()] == ["room.usda"]  # no temporary file left


def test_a_file_name_that_is_not_usd_is_refused(tmp_path):
    with pytest.raises(InputError):
        export_usd(market_scene(), tmp_path / "scene.obj")
