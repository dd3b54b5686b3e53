#include "pipeline/cloud/kdtree.h"

#include <nanoflann.hpp>

#include <cmath>
#include <utility>

namespace efc::pipeline {

namespace {

// nanoflann's dataset interface over the finite points: `ids` maps the tree's
// dense indices back to the caller's (empty when every point is finite).
struct Dataset {
  const std::vector<Eigen::Vector3d>* points = nullptr;
  std::vector<size_t> ids;
  size_t count = 0;

  size_t original(size_t i) const { return ids.empty() ? i : ids[i]; }
  size_t kdtree_get_point_count() const { return count; }
  double kdtree_get_pt(size_t i, size_t dim) const { return (*points)[original(i)][static_cast<int>(dim)]; }
  template <class BBOX>
  bool kdtree_get_bbox(BBOX&) const { return false; }
};

using Index = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Dataset>, Dataset, 3, size_t>;

}  // namespace

struct KdTree::Impl {
  Dataset data;                 // before `index`: the index keeps a reference to it
  std::unique_ptr<Index> index;  // null when no point is finite
};

KdTree::KdTree(const std::vector<Eigen::Vector3d>& points) : impl_(new Impl) {
  impl_->data.points = &points;
  bool all_finite = true;
  for (const auto& p : points) all_finite = all_finite && p.allFinite();
  if (all_finite) {
    impl_->data.count = points.size();
  } else {
    for (size_t i = 0; i < points.size(); ++i)
      if (points[i].allFinite()) impl_->data.ids.push_back(i);
    impl_->data.count = impl_->data.ids.size();
  }
  if (impl_->data.count > 0)
    impl_->index.reset(new Index(3, impl_->data, nanoflann::KDTreeSingleIndexAdaptorParams(10)));
}

KdTree::~KdTree() = default;

size_t KdTree::size() const { return impl_->data.count; }

bool KdTree::nearest(const Eigen::Vector3d& q, size_t* index, double* dist2) const {
  if (!impl_->index || !q.allFinite()) return false;
  size_t i = 0;
  double d2 = 0;
  if (impl_->index->knnSearch(q.data(), 1, &i, &d2) < 1) return false;
  if (index != nullptr) *index = impl_->data.original(i);
  if (dist2 != nullptr) *dist2 = d2;
  return true;
}

bool KdTree::nearest_within(const Eigen::Vector3d& q, double r, size_t* index, double* dist2) const {
  if (!impl_->index || !q.allFinite() || !(r > 0) || !std::isfinite(r)) return false;
  size_t i = 0;
  double d2 = 0;
  nanoflann::KNNResultSet<double, size_t, size_t> result(1);
  result.init(&i, &d2);
  // The one slot starts r^2 away: the tree only descends where a point can
  // beat it, and only such a point is taken.
  d2 = r * r;
  impl_->index->findNeighbors(result, q.data(), nanoflann::SearchParams());
  if (result.size() < 1) return false;
  if (index != nullptr) *index = impl_->data.original(i);
  if (dist2 != nullptr) *dist2 = d2;
  return true;
}

void KdTree::knn(const Eigen::Vector3d& q, size_t k, std::vector<size_t>* indices, std::vector<double>* dist2) const {
  std::vector<size_t> idx;
  std::vector<double> d2;
  if (impl_->index && q.allFinite() && k > 0) {
    k = std::min(k, impl_->data.count);
    idx.resize(k);
    d2.resize(k);
    const size_t found = impl_->index->knnSearch(q.data(), k, idx.data(), d2.data());
    idx.resize(found);
    d2.resize(found);
    for (auto& i : idx) i = impl_->data.original(i);
  }
  if (indices != nullptr) *indices = std::move(idx);
  if (dist2 != nullptr) *dist2 = std::move(d2);
}

void KdTree::radius(const Eigen::Vector3d& q, double r, std::vector<size_t>* indices) const {
  if (indices == nullptr) return;
  indices->clear();
  if (!impl_->index || !q.allFinite() || !(r > 0) || !std::isfinite(r)) return;
  std::vector<std::pair<size_t, double>> found;
  impl_->index->radiusSearch(q.data(), r * r, found, nanoflann::SearchParams(32, 0, true));
  indices->reserve(found.size());
  for (const auto& f : found) indices->push_back(impl_->data.original(f.first));
}

}  // namespace efc::pipeline
