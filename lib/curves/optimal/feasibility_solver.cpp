#include "curves/optimal/feasibility_solver.hpp"

#include <memory>
#include <utility>

#include "curves/optimal/feasibility_solver_impl.hpp"

namespace sculpt::curves::detail {

FeasibilitySolver::FeasibilitySolver(const std::vector<Eigen::Vector3d>& points, Norm norm, std::vector<int> vertices,
                                     const SegmentErrorTree* shared_tree)
    : impl_(std::make_unique<Impl>(points, norm, std::move(vertices), shared_tree)) {}
FeasibilitySolver::~FeasibilitySolver() = default;

int FeasibilitySolver::count() const { return impl_->count(); }
const std::vector<int>& FeasibilitySolver::vertices() const { return impl_->vertices(); }
double FeasibilitySolver::error(int a, int b) { return impl_->error(a, b); }
long long FeasibilitySolver::edge_count() const { return impl_->edge_count(); }
double FeasibilitySolver::evaluation_cost() const { return impl_->evaluation_cost(); }
void FeasibilitySolver::store_errors(double limit) { impl_->store_errors(limit); }
const std::vector<double>& FeasibilitySolver::stored_errors() const { return impl_->stored_errors(); }
bool FeasibilitySolver::build_rows(double limit, double budget, double floor) {
  return impl_->build_rows(limit, budget, floor);
}
double FeasibilitySolver::floor() const { return impl_->floor(); }
void FeasibilitySolver::materialize() { impl_->materialize(); }
long long FeasibilitySolver::tests() const { return impl_->tests(); }
void FeasibilitySolver::prune_reach(double eps) { impl_->prune_reach(eps); }
double FeasibilitySolver::reach_eps() const { return impl_->reach_eps(); }
void FeasibilitySolver::min_count(double eps) { impl_->min_count(eps); }
int FeasibilitySolver::min_segments() const { return impl_->min_segments(); }
std::vector<int> FeasibilitySolver::min_path() const { return impl_->min_path(); }
ExactPath FeasibilitySolver::exact_path(double eps, int m) { return impl_->exact_path(eps, m); }
std::vector<int> FeasibilitySolver::indices(const std::vector<int>& path) const { return impl_->indices(path); }

}  // namespace sculpt::curves::detail
