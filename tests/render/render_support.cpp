#include "tests/render/render_support.h"

#include <cstdlib>
#include <filesystem>
#include <map>

namespace sketchsurf::testing {

const vk::Context& render_context() {
  static const auto context = std::make_unique<vk::Context>(vk::ContextOptions{});
  return *context;
}

render::RgbaImage render_picture(const render::SceneGeometry& geometry, int width, int height,
                                 render::View view, const render::DrawOptions& draw) {
  render::HeadlessRenderer renderer(render_context(), width, height);
  renderer.set_scene(geometry);
  return renderer.render(render::fit_camera(geometry.bounds, view, double(width) / height), draw);
}

std::vector<int> box_face_labels(const TriMesh& mesh, const Eigen::Vector3d& half) {
  std::vector<int> labels;
  for (auto v : mesh.vertices()) {
    const Eigen::Vector3d p = to_eigen(mesh.point(v)).cwiseQuotient(half);
    int axis = 0;
    p.cwiseAbs().maxCoeff(&axis);
    labels.push_back(2 * axis + (p[axis] < 0.0 ? 1 : 0));
  }
  return labels;
}

TriMesh box_grid_mesh(int n, const Eigen::Vector3d& half) {
  std::vector<Eigen::Vector3d> points;
  std::map<std::array<long, 3>, int> index;  // vertices shared along the box's edges
  auto vertex = [&](const Eigen::Vector3d& unit) {
    const std::array<long, 3> key{std::lround(unit.x() * n), std::lround(unit.y() * n),
                                  std::lround(unit.z() * n)};
    auto [it, inserted] = index.emplace(key, int(points.size()));
    if (inserted) points.push_back(unit.cwiseProduct(half));
    return it->second;
  };
  std::vector<Eigen::Vector3i> faces;
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {1.0, -1.0}) {
      // (u, v, normal) right-handed, so that counter-clockwise quads face outwards.
      Eigen::Vector3d normal = Eigen::Vector3d::Zero(), u = normal, v = normal;
      normal[axis] = sign;
      u[(axis + 1) % 3] = 1.0;
      v = normal.cross(u);
      auto at = [&](int i, int j) {
        return vertex(normal + u * (2.0 * i / n - 1.0) + v * (2.0 * j / n - 1.0));
      };
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          faces.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
          faces.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    }
  Eigen::MatrixX3d V(points.size(), 3);
  for (std::size_t i = 0; i < points.size(); ++i) V.row(i) = points[i].transpose();
  Eigen::MatrixX3i F(faces.size(), 3);
  for (std::size_t i = 0; i < faces.size(); ++i) F.row(i) = faces[i].transpose();
  return mesh_from_matrices(V, F);
}

void expect_golden(const render::RgbaImage& actual, const std::string& name) {
  const std::filesystem::path golden =
      std::filesystem::path(SKETCHSURF_TESTS_DIR) / "render" / "golden" / (name + ".png");
  const char* update = std::getenv("SKETCHSURF_UPDATE_GOLDEN");
  if (update && std::string(update) == "1") {
    render::write_png(actual, golden);
    std::cout << "wrote golden image " << golden << "\n";
    return;
  }
  ASSERT_TRUE(std::filesystem::exists(golden))
      << golden << " is missing; run the test with SKETCHSURF_UPDATE_GOLDEN=1 to make it";
  const render::RgbaImage expected = render::read_png(golden);
  const render::ImageComparison cmp = render::compare_images(expected, actual, 8);
  if (cmp.same_size && cmp.fraction < 0.01) return;
  const std::filesystem::path out_actual = name + "_actual.png", out_diff = name + "_diff.png";
  render::write_png(actual, out_actual);
  render::write_png(render::difference_image(expected, actual, 8), out_diff);
  ADD_FAILURE() << name << ": " << (cmp.same_size ? "" : "size differs; ") << cmp.differing
                << " pixels (" << 100.0 * cmp.fraction << "%) differ by more than 8/255 (max "
                << cmp.max_difference << "); see " << std::filesystem::absolute(out_actual)
                << " and " << std::filesystem::absolute(out_diff);
}

std::size_t non_background_pixels(const render::RgbaImage& image, const render::Rgb8& background) {
  std::size_t count = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const auto p = image.at(x, y);
      for (int c = 0; c < 3; ++c)
        if (std::abs(int(p[c]) - int(background[c])) > 8) {
          ++count;
          break;
        }
    }
  return count;
}

}  // namespace sketchsurf::testing
