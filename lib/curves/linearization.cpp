#include "curves/linearization.hpp"

#include "base/errors.hpp"

namespace sculpt::curves {

std::vector<Eigen::Vector3d> linearization_points(const DigitizedCurve& curve, const Linearization& la) {
  const std::vector<Eigen::Vector3d> path = path_points(curve);
  std::vector<Eigen::Vector3d> result;
  result.reserve(la.indices.size());
  for (int index : la.indices) {
    if (index < 0 || index >= static_cast<int>(path.size()))
      throw InvalidInput("linearization index " + std::to_string(index) + " is outside the curve");
    result.push_back(path[index]);
  }
  return result;
}

double linearization_error(const DigitizedCurve& curve, const Linearization& la, Norm norm) {
  const std::vector<Eigen::Vector3d> path = path_points(curve);
  const int last = static_cast<int>(path.size()) - 1;
  if (la.indices.size() < 2 || la.indices.front() != 0 || la.indices.back() != last)
    throw InvalidInput("linearization must start at index 0 and end at index " + std::to_string(last));
  for (std::size_t k = 0; k + 1 < la.indices.size(); ++k)
    if (la.indices[k] >= la.indices[k + 1]) throw InvalidInput("linearization indices must strictly increase");
  return approximation_error(path, la.indices, norm);
}

}  // namespace sculpt::curves
