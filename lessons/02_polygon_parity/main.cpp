// Lesson 02: the plane hit and containment by parity — the demonstration.
//
// Stars, a notched comb and a polygon with holes standing on a checkered
// ground plane, one primary ray per pixel through the pinhole camera: each
// ray meets each polygon's plane (geometry/plane.hpp, erratum 2), and parity
// (geometry/parity.hpp) decides whether the point is inside. Writes the
// picture and prints its size. The studies the text quotes run in its order,
// one file each in studies/ (README.md, "Read in this order").
#include <cmath>
#include <iostream>
#include <vector>

#include "illum/core/image.hpp"
#include "illum/core/pinhole_camera.hpp"
#include "illum/geometry/parity.hpp"
#include "illum/geometry/plane.hpp"
#include "illum/geometry/polygon.hpp"
#include "illum/io/output_folder.hpp"
#include "illum/io/program.hpp"
#include "outlines.hpp"
#include "studies/studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson02 {
namespace {

struct Shape {
  Polygon polygon;
  Color color;
};

// Stars, a notched comb and a frame with three holes standing on a checkered
// ground plane, one primary ray per pixel: the plane hit (erratum 2), the
// bounding rectangle, then parity (geometry/polygon.hpp).
Image render_polygons(int width, int height) {
  const Vec3 up(0, 1, 0);
  const Vec3 tilt_right = normalize(Vec3(1, 0, -0.35)), tilt_left = normalize(Vec3(1, 0, 0.35));
  std::vector<Shape> shapes;
  shapes.push_back(
      {Polygon(place(star(5, 1.3, 0.5), Point3(-3.1, 0.4, 0), tilt_left, up)), Color(0.9, 0.6, 0.1)});
  shapes.push_back(
      {Polygon(place(comb(4, 2.4, 1.6), Point3(0, 0.1, -0.5), Vec3(1, 0, 0), up)), Color(0.2, 0.6, 0.9)});
  // A frame with three holes: a square, a triangle and a 24-gon, wound either way.
  std::vector<std::vector<Point3>> holes{
      place({{-0.8, 0.2}, {-0.8, 0.8}, {-0.2, 0.8}, {-0.2, 0.2}}, Point3(3.1, 0.2, 0), tilt_right, up),
      place({{0.2, 0.2}, {0.8, 0.2}, {0.5, 0.8}}, Point3(3.1, 0.2, 0), tilt_right, up),
      place(regular(24, 0.45, {0.0, -0.5}, true), Point3(3.1, 0.2, 0), tilt_right, up)};
  shapes.push_back({Polygon(place({{-1.1, -1.1}, {1.1, -1.1}, {1.1, 1.1}, {-1.1, 1.1}}, Point3(3.1, 0.2, 0),
                                  tilt_right, up),
                            holes),
                    Color(0.8, 0.25, 0.3)});
  // A small star lying flat on the ground: its normal is mostly y, so y is dropped.
  shapes.push_back({Polygon(place(star(7, 0.9, 0.45), Point3(0, -1.49, 2.2), Vec3(1, 0, 0), Vec3(0, 0, 1))),
                    Color(0.95, 0.9, 0.3)});
  const Plane ground(Vec3(0, 1, 0), 1.5);  // y = −1.5
  const Vec3 light = normalize(Vec3(-0.4, 0.8, 0.6));

  const PinholeCamera camera(Point3(0, 1.2, 8.5), Point3(0, -0.2, 0), up, 45.0, width, height);
  Image image(width, height);
  // One call outside the parallel loop, so that an error (or an exercise's
  // NotImplemented) reaches run_program instead of terminating an OpenMP thread.
  (void)intersect(camera.pixel_ray(0, 0), shapes[0].polygon);
#pragma omp parallel for schedule(dynamic, 4)
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const Ray ray = camera.pixel_ray(i, j);
      double nearest = infinity;
      Color color = Color(0.55, 0.65, 0.8) * (0.6 + 0.4 * ray.direction.y);  // sky
      for (const Shape& shape : shapes) {
        const auto hit = intersect(ray, shape.polygon);
        if (hit && hit->s < nearest) {
          nearest = hit->s;
          color = shape.color * (0.25 + 0.75 * std::abs(dot(hit->normal, light)));
        }
      }
      if (const auto s = intersect(ray, ground); s && *s < nearest) {
        const Point3 p = ray.at(*s);
        const bool dark = (static_cast<int>(std::floor(p.x)) + static_cast<int>(std::floor(p.z))) % 2 != 0;
        color = (dark ? Color(0.3) : Color(0.7)) * (0.25 + 0.75 * light.y);
      }
      image.at(i, j) = color;
    }
  return image;
}

}  // namespace
}  // namespace illum::lesson02

int main(int argc, char** argv) {
  using namespace illum;
  const ProgramInfo info{
      "lesson02", "The plane hit and containment by parity",
      "Renders polygons (stars, a comb, a polygon with holes) through the pinhole camera, "
      "checks a tiling under three boundary rules, and measures the parity test's cost "
      "against the vertex count.",
      TimedCores::one};  // every timing on one thread: the main job may run it beside another
  return run_program(argc, argv, info, {}, [&](const ProgramOptions& options) {
    const lesson02::Settings settings{.quick = options.quick, .seed = options.seed};
    OutputFolder out(options.out, info.id, info.title);
    run_section(info.id, "§4 Crossing parity and the half-open rule",
                [&] { lesson02::s04_tiling_rules(out, settings); });
    run_section(info.id, "§6 The ray–polygon hit", [&] {
      const int width = settings.quick ? 240 : 960, height = settings.quick ? 135 : 540;
      out.image(
          lesson02::render_polygons(width, height), "polygons",
          "Stars, a notched comb and a frame with three holes, hit by ray–plane (erratum 2) plus parity");
      std::cout << "polygons: " << width << " × " << height
                << " primary rays, each against 4 polygons and the ground\n";
    });
    run_section(info.id, "§7 What it costs", [&] { lesson02::s07_parity_cost(out, settings); });
    out.finish();
  });
}
