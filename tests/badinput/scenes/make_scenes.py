#!/usr/bin/env python3
"""Writes the bad scenes of tests/badinput/cases.txt (run it here after a
format change): each is a valid scene of docs/scene-format.md with one thing
wrong, named by its file name. r_*: radiosity scenes (lesson 11 --scene),
s_*: scenes of spheres (illum render)."""
import copy
import json

CAMERA = {"eye": [50, 50, -200], "target": [50, 50, 50], "up": [0, 1, 0], "vertical_fov_degrees": 40,
          "width": 64, "height": 64}
RADIOSITY = {
    "format": 1, "name": "two quads", "camera": CAMERA,
    "materials": {"white": {"diffuse": [0.7, 0.7, 0.7]},
                  "light": {"diffuse": [0.5, 0.5, 0.5], "emission": [10, 10, 10]}},
    "primitives": [
        {"type": "polygon", "name": "floor", "material": "white",
         "vertices": [[0, 0, 0], [0, 0, 100], [100, 0, 100], [100, 0, 0]]},
        {"type": "polygon", "name": "light", "material": "light",
         "vertices": [[0, 100, 0], [100, 100, 0], [100, 100, 100], [0, 100, 100]]}]}
SPHERES = {
    "format": 1,
    "camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "up": [0, 1, 0], "vertical_fov_degrees": 45,
               "width": 32, "height": 24},
    "materials": {"red": {"diffuse": [0.8, 0.3, 0.2]}},
    "primitives": [{"type": "sphere", "name": "ball", "material": "red", "center": [0, 0, 0], "radius": 1}]}


def write(name, scene):
    with open(name, "w") as f:
        f.write(scene if isinstance(scene, str) else json.dumps(scene, indent=1) + "\n")


def variant(base, change):
    s = copy.deepcopy(base)
    change(s)
    return s


def rename(d, old, new):
    d[new] = d.pop(old)


def floor(s, vertices):
    s["primitives"][0]["vertices"] = vertices


R, S = RADIOSITY, SPHERES
write("r_valid.json", R)
write("r_emision_typo.json", variant(R, lambda s: rename(s["materials"]["light"], "emission", "emision")))
write("r_difuse_typo.json", variant(R, lambda s: rename(s["materials"]["white"], "diffuse", "difuse")))
write("r_primitives_typo.json", variant(R, lambda s: rename(s, "primitives", "primitivs")))
write("r_vertices_typo.json", variant(R, lambda s: rename(s["primitives"][0], "vertices", "vertexes")))
write("r_camera_typo.json", variant(R, lambda s: s["camera"].update(fov=40)))
write("r_camera_nan.json", variant(R, lambda s: s["camera"].update(eye=[50, "NaN", -200])))
write("r_camera_null.json", variant(R, lambda s: s["camera"].update(up=[0, None, 0])))
write("r_camera_1e999.json", json.dumps(R).replace('"eye": [50, 50, -200]', '"eye": [50, 1e999, -200]'))
write("r_eye_target.json", variant(R, lambda s: s["camera"].update(target=[50, 50, -200])))
write("r_up_parallel.json", variant(R, lambda s: s["camera"].update(up=[0, 0, 2])))
write("r_no_camera.json", variant(R, lambda s: s.pop("camera")))
write("r_zero_reflectance.json",
      variant(R, lambda s: [m.update(diffuse=[0, 0, 0]) for m in s["materials"].values()]))
write("r_no_emission.json", variant(R, lambda s: s["materials"]["light"].pop("emission")))
write("r_nonplanar.json", variant(R, lambda s: floor(s, [[0, 0, 0], [0, 0, 100], [100, 1, 100], [100, 0, 0]])))
write("r_huge_wall.json", variant(R, lambda s: floor(s, [[0, 0, 0], [0, 0, 1e9], [1e9, 0, 1e9], [1e9, 0, 0]])))
write("r_big_for_study.json",
      variant(R, lambda s: floor(s, [[0, 0, 0], [0, 0, 10000], [10000, 0, 10000], [10000, 0, 0]])))
write("r_nonconvex.json", variant(R, lambda s: floor(s, [[0, 0, 0], [100, 0, 100], [0, 0, 100], [100, 0, 0]])))
write("r_degenerate.json", variant(R, lambda s: floor(s, [[0, 0, 0], [50, 0, 50], [100, 0, 100]])))
write("r_reflectance_one.json", variant(R, lambda s: s["materials"]["white"].update(diffuse=[1.0, 0.5, 0.5])))
write("r_negative_emission.json", variant(R, lambda s: s["materials"]["light"].update(emission=[10, -1, 10])))
write("r_unknown_material.json", variant(R, lambda s: s["primitives"][0].update(material="whyte")))
write("r_five_vertices.json", variant(R, lambda s: s["primitives"][0]["vertices"].append([50, 0, -20])))
write("r_sphere.json", variant(R, lambda s: s["primitives"].append(
    {"type": "sphere", "material": "white", "center": [50, 50, 50], "radius": 10})))
# t_*: scenes of lesson 13 (two passes: specular spheres in the radiosity scene).
write("t_specular_over_one.json", variant(R, lambda s: (
    s["materials"].update(glass={"reflectance": [0.5, 0.5, 0.5], "transmittance": [0.6, 0.6, 0.6]}),
    s["primitives"].append({"type": "sphere", "material": "glass", "center": [50, 50, 50], "radius": 10}))))
write("t_csg_occluder.json", variant(R, lambda s: s["primitives"].append(
    {"type": "csg", "material": "white", "solid": {"solid": "box", "min": [40, 0, 40], "max": [60, 20, 60]}})))
write("t_no_emitter.json", variant(R, lambda s: s["materials"]["light"].pop("emission")))
write("r_empty_primitives.json", variant(R, lambda s: s.update(primitives=[])))
write("r_primitive_not_object.json", variant(R, lambda s: s["primitives"].append(3)))
write("r_not_json.json", '{ "primitives": [ { "material": "white", } ] \n')
write("r_top_array.json", "[1, 2, 3]\n")

write("s_valid.json", S)
write("s_colour_field.json", variant(S, lambda s: rename(s["materials"]["red"], "diffuse", "colour")))
write("s_difuse_typo.json", variant(S, lambda s: rename(s["materials"]["red"], "diffuse", "difuse")))
write("s_radius_typo.json", variant(S, lambda s: rename(s["primitives"][0], "radius", "raduis")))
write("s_top_typo.json", variant(S, lambda s: rename(s, "primitives", "primitive")))
write("s_no_format.json", variant(S, lambda s: s.pop("format")))
write("s_eye_target.json", variant(S, lambda s: s["camera"].update(target=[0, 0, 3])))
write("s_up_parallel.json", variant(S, lambda s: s["camera"].update(up=[0, 0, -5])))
write("s_camera_string.json", variant(S, lambda s: s["camera"].update(eye="here")))
write("s_camera_1e999.json", json.dumps(S).replace('"target": [0, 0, 0]', '"target": [0, -1e999, 0]'))
write("s_width_zero.json", variant(S, lambda s: s["camera"].update(width=0)))
write("s_width_fraction.json", variant(S, lambda s: s["camera"].update(width=31.5)))
write("s_huge_image.json", variant(S, lambda s: s["camera"].update(width=16384, height=16384)))
write("s_radius_negative.json", variant(S, lambda s: s["primitives"][0].update(radius=-2)))
write("s_color_above_one.json", variant(S, lambda s: s["materials"]["red"].update(diffuse=[0.5, 1.5, 0.5])))
write("s_fov_180.json", variant(S, lambda s: s["camera"].update(vertical_fov_degrees=180)))
write("s_empty_primitives.json", variant(S, lambda s: s.update(primitives=[])))
write("s_primitive_not_object.json", variant(S, lambda s: s["primitives"].append([1, 2, 3])))
write("s_polygon.json", variant(S, lambda s: s["primitives"].append(
    {"type": "polygon", "material": "red", "vertices": [[0, 0, -2], [1, 0, -2], [0, 1, -2]]})))
write("s_no_camera.json", variant(S, lambda s: s.pop("camera")))
write("s_not_json.json", '{"camera": {"eye": [0, 0, 3]')
write("s_top_string.json", '"primitives"\n')

# lesson 07: the procedural checker of a polygon
def checkered(checker):
    def change(s):
        s["materials"]["white"] = {"diffuse": [0.8, 0.8, 0.8]}
        s["primitives"].append({"type": "polygon", "name": "board", "material": "white", "checker": checker,
                                "vertices": [[-5, -1, -5], [-5, -1, 5], [5, -1, 5], [5, -1, -5]]})
    return change


write("s_checker_unknown_material.json", variant(S, checkered({"material": "blak", "size": 1})))
write("s_checker_size_zero.json", variant(S, checkered({"material": "red", "size": 0})))
write("s_checker_size_typo.json", variant(S, checkered({"material": "red", "sise": 1})))

# Cameras beyond the range where squared distances fit a double (issue 25).
write("s_camera_far.json", variant(S, lambda s: s["camera"].update(eye=[1e308, 1e308, 1e308])))
write("s_camera_apart.json", variant(S, lambda s: s["camera"].update(eye=[-1e308, 0, 0], target=[1e308, 0, 0])))
write("r_camera_far.json", variant(R, lambda s: s["camera"].update(target=[50, 50, -1e308])))
# A camera whose image cannot fit in a memory limit (run under `ulimit -v`): 13,000 × 13,000.
write("s_big_camera.json", variant(S, lambda s: s["camera"].update(width=13000, height=13000)))


# m_*: a scene of one OBJ mesh (illum render), and the mesh it names with one thing wrong.
def mesh_scene(obj, **fields):
    s = variant(S, lambda s: s["primitives"].__setitem__(
        0, {"type": "mesh", "name": "mesh", "material": "red", "obj": obj, **fields}))
    s["camera"].update(eye=[0.5, 0.5, 3], target=[0.5, 0.5, 0])
    return s


TRIANGLE = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
MESHES = {
    "index_wraps": TRIANGLE + "f 1 2 3\nf 1 2 4294967299\n",
    "index_huge": TRIANGLE + "f 1 2 3\nf 1 2 99999999999999999999\n",
    "index_zero": TRIANGLE + "f 0 1 2\n",
    "index_negative": TRIANGLE + "f -1 -2 -3\nf -1 -2 -5\n",
    "index_beyond": TRIANGLE + "f 1 2 3\nf 1 2 7\n",
    "vertex_nan": "v nan 1 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    "vertex_inf": "v 0 0 0\nv 1 -inf 0\nv 0 1 0\nf 1 2 3\n",
    "vertex_word": "v 0 one 1\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    "vertex_overflow": "v 0 0 0\nv 1 1e999 0\nv 0 1 0\nf 1 2 3\n",
    "vertex_two_numbers": "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    "two_corners": TRIANGLE + "f 1 2 3\nf 1 2\n",
    "one_corner_last": TRIANGLE + "f 1 2 3\n" * 3 + "f 3",
    "normal_missing": TRIANGLE + "vn 0 0 1\nf 1//1 2//1 3//2\n",
    "normal_zero": TRIANGLE + "vn 0 0 0\nf 1//1 2//1 3//1\n",
    "corner_garbage": TRIANGLE + "f 1 2/x 3\n",
    "degenerate": TRIANGLE + "f 1 1 2\n",
    "free_form": TRIANGLE + "f 1 2 3\ncurv 0 1 1 2\n",
    "unknown_statement": TRIANGLE + "f 1 2 3\nvx 1 2 3\n",
    "no_faces": TRIANGLE,
    "binary": "\x7fELF\x02\x01\x01\x00\x00\x00",
}
for name, text in MESHES.items():
    with open(f"m_{name}.obj", "w") as f:
        f.write(text)
    write(f"m_{name}.json", mesh_scene(f"m_{name}.obj"))
write("m_folder.json", mesh_scene("."))               # the scenes folder itself
write("m_dev_zero.json", mesh_scene("/dev/zero"))     # an absolute path: a device that never ends
write("m_fifo.json", mesh_scene("pipe.obj"))          # copied beside a FIFO named pipe.obj by the case
write("m_scale_overflow.json", mesh_scene("m_big_vertex.obj", scale=1e300))
with open("m_big_vertex.obj", "w") as f:
    f.write("v 0 0 0\nv 1e10 0 0\nv 0 1 0\nf 1 2 3\n")

# Issue 50: files of an older format, magnitudes that overflow later, a byte-order mark.
write("s_old_sphere_format.json", {
    "description": "the sphere-only format of the first lessons, before format 1",
    "camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "up": [0, 1, 0], "vertical_fov_degrees": 45,
               "width": 32, "height": 24},
    "spheres": [{"name": "ball", "center": [0, 0, 0], "radius": 1, "color": [0.8, 0.3, 0.2]}]})
write("r_old_radiosity_format.json", {
    "name": "two quads, before format 1", "camera": {"eye": [50, 50, -200], "target": [50, 50, 50],
                                                     "up": [0, 1, 0], "vertical_fov_degrees": 40},
    "materials": {"white": {"reflectance": [0.7, 0.7, 0.7]},
                  "light": {"reflectance": [0.5, 0.5, 0.5], "emission": [10, 10, 10]}},
    "surfaces": [{"name": "floor", "material": "white",
                  "polygon": [[0, 0, 0], [0, 0, 100], [100, 0, 100], [100, 0, 0]]},
                 {"name": "light", "material": "light",
                  "polygon": [[0, 100, 0], [100, 100, 0], [100, 100, 100], [0, 100, 100]]}]})
# Every coordinate and size of a scene lies within ±1e150, as a camera's (squares stay within a double).
write("s_sphere_far.json", variant(S, lambda s: s["primitives"][0].update(center=[1e300, 0, 0])))
write("s_radius_huge.json", variant(S, lambda s: s["primitives"][0].update(radius=1e200)))
write("s_light_far.json", variant(S, lambda s: s.update(
    lights=[{"type": "point", "position": [0, 1e200, 0], "intensity": [1, 1, 1]}])))
write("s_ior_huge.json", variant(S, lambda s: s["materials"]["red"].update(
    index_of_refraction=1e300, transmittance=[0.5, 0.5, 0.5])))
write("r_polygon_far.json", variant(R, lambda s: floor(s, [[0, 0, 0], [0, 0, 100], [1e200, 0, 100], [1e200, 0, 0]])))
write("r_emission_huge.json", variant(R, lambda s: s["materials"]["light"].update(emission=[1e200, 10, 10])))
write("m_scale_beyond.json", mesh_scene("m_big_vertex.obj", scale=1e145))  # its vertex at 1e10 goes to 1e155
with open("m_vertex_huge.obj", "w") as f:
    f.write("v 0 0 0\nv 1e308 0 0\nv 0 1 0\nf 1 2 3\n")
write("m_vertex_huge.json", mesh_scene("m_vertex_huge.obj"))
# A valid mesh whose file starts with a UTF-8 byte-order mark, in a scene whose second primitive is
# wrong: the refusal names that primitive, so the mesh was read.
with open("m_bom.obj", "w", encoding="utf-8") as f:
    f.write("\ufeff" + TRIANGLE + "f 1 2 3\n")
write("m_bom.json", variant(mesh_scene("m_bom.obj"), lambda s: s["primitives"].append(
    {"type": "sphere", "name": "ball", "material": "blak", "center": [0, 0, 0], "radius": 1})))
# A camera twice as tall as wide: the lab's width=2048 makes a 2048 × 4096 image.
write("s_tall_camera.json", variant(S, lambda s: s["camera"].update(width=32, height=64)))
write("m_loop.json", mesh_scene("loop.obj"))  # copied beside a link loop named loop.obj by the case
