// A card's parameter covariance and seeded draws from it (covariance.hpp).
#include "fitlib/card/covariance.hpp"

#include <algorithm>
#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/core/rng.hpp"

namespace fitlib::card {
namespace {

using core::InputError;

// fit.covariance: {"parameters": [names], "coordinates": ["ln"|"value"], "matrix": [[...]]}.
CardCovariance stored_covariance(const Card& card, const nlohmann::json& j, const std::string& source) {
  const std::string key = "fit.covariance";
  if (!j.is_object() || !j.contains("parameters") || !j.contains("coordinates") || !j.contains("matrix") ||
      !j["parameters"].is_array() || !j["coordinates"].is_array() || !j["matrix"].is_array())
    throw InputError("expected an object with arrays parameters, coordinates and matrix", source, 0, 0, key);
  const std::size_t n = j["parameters"].size();
  if (j["coordinates"].size() != n || j["matrix"].size() != n)
    throw InputError("parameters, coordinates and matrix must have the same length", source, 0, 0, key);
  const model::ModelPtr model = card.model();  // held: parameters() refers into it
  std::vector<std::string> names;
  for (const auto& spec : model->parameters()) names.push_back(spec.name);
  CardCovariance c;
  c.matrix.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  for (std::size_t a = 0; a < n; ++a) {
    const auto& name = j["parameters"][a];
    const auto at = name.is_string() ? std::find(names.begin(), names.end(), name.get<std::string>()) : names.end();
    if (at == names.end()) throw InputError("not a parameter of the card's model", source, 0, 0, key + ".parameters");
    c.index.push_back(static_cast<int>(at - names.begin()));
    const auto& coord = j["coordinates"][a];
    if (coord != "ln" && coord != "value")
      throw InputError("coordinates are \"ln\" or \"value\"", source, 0, 0, key + ".coordinates");
    c.log.push_back(coord == "ln");
    if (c.log.back() && !(card.parameters[c.index.back()].value > 0.0))
      throw InputError("an \"ln\" coordinate needs a positive value", source, 0, 0, key + ".coordinates");
    const auto& row = j["matrix"][a];
    if (!row.is_array() || row.size() != n) throw InputError("the matrix must be square", source, 0, 0, key + ".matrix");
    for (std::size_t b = 0; b < n; ++b) {
      if (!row[b].is_number() || !std::isfinite(row[b].get<double>()))
        throw InputError("the matrix holds finite numbers", source, 0, 0, key + ".matrix");
      c.matrix(a, b) = row[b].get<double>();
    }
  }
  if (!c.matrix.isApprox(c.matrix.transpose(), 1e-9))
    throw InputError("the matrix must be symmetric", source, 0, 0, key + ".matrix");
  return c;
}

}  // namespace

std::optional<CardCovariance> card_covariance(const Card& card, const std::string& source) {
  if (card.fit.contains("covariance")) return stored_covariance(card, card.fit["covariance"], source);
  CardCovariance c;
  c.correlated = false;
  std::vector<double> var;
  for (std::size_t i = 0; i < card.parameters.size(); ++i) {
    const ParameterEstimate& p = card.parameters[i];
    if (p.fixed || !p.std_error || !(*p.std_error > 0.0)) continue;
    const bool log = p.value > 0.0;  // a positive value varies in ln p (its std error σ/p there)
    c.index.push_back(static_cast<int>(i));
    c.log.push_back(log);
    var.push_back(std::pow(log ? *p.std_error / p.value : *p.std_error, 2));
  }
  if (var.empty()) return std::nullopt;
  c.matrix = Eigen::Map<Eigen::VectorXd>(var.data(), static_cast<Eigen::Index>(var.size())).asDiagonal();
  return c;
}

namespace {

// SplitMix64's finaliser: one engine seed per (seed, stream, draw), so draw k depends on nothing else.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

}  // namespace

CardSampler::CardSampler(const Card& card, CardCovariance covariance)
    : values_(card.values()), covariance_(std::move(covariance)) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(covariance_.matrix);
  if (eig.info() != Eigen::Success || eig.eigenvalues().minCoeff() < -1e-9 * std::abs(eig.eigenvalues().maxCoeff()))
    throw core::InputError("fit.covariance is not positive semi-definite");
  root_ = eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal();
}

std::vector<double> CardSampler::draw(std::uint64_t seed, std::uint64_t stream, std::uint64_t k) const {
  core::Rng rng(mix(mix(mix(seed) ^ stream) ^ k));
  Eigen::VectorXd z(static_cast<Eigen::Index>(covariance_.index.size()));
  for (Eigen::Index a = 0; a < z.size(); ++a) z[a] = rng.normal();
  const Eigen::VectorXd dx = root_ * z;
  std::vector<double> v = values_;
  for (std::size_t a = 0; a < covariance_.index.size(); ++a) {
    double& p = v[covariance_.index[a]];
    p = covariance_.log[a] ? p * std::exp(dx[static_cast<Eigen::Index>(a)]) : p + dx[static_cast<Eigen::Index>(a)];
  }
  return v;
}

}  // namespace fitlib::card
