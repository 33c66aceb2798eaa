#pragma once
// The stabilization of the discrete operator: SUPG's delta0, its cell length and its
// bound by the slab length (doc/method.md §3). Space takes it; the discretization
// section of a config derives from it. A new stabilization term adds its parameters
// here.
#include "base/choice.h"

#include <vector>

namespace anisodwr
{
/// discretization.supg_length: the cell length h_K in delta_K = delta0 h_K.
enum class SupgLength
{
  volume,    ///< |K|^(1/d)
  streamline ///< the length of K along b at its centre
};

inline const std::vector<Named<SupgLength>> &names(SupgLength)
{
  static const std::vector<Named<SupgLength>> table{
      {SupgLength::volume, "volume"}, {SupgLength::streamline, "streamline"}};
  return table;
}

/// How the crosswind diffusion is switched on (Stabilization::crosswind_form).
enum class CrosswindForm
{
  linear,
  residual
};

inline const std::vector<Named<CrosswindForm>> &names(CrosswindForm)
{
  static const std::vector<Named<CrosswindForm>> table{{CrosswindForm::linear, "linear"},
                                                       {CrosswindForm::residual, "residual"}};
  return table;
}

struct Stabilization
{
  /// delta_K = delta0 h_K; 0 turns SUPG off
  double delta0 = 1.0;
  /// h_K = |K|^(1/d) (volume) or the length of K along b at its centre (streamline)
  SupgLength supg_length = SupgLength::volume;
  /// delta_K <= supg_tau_factor * tau_n on a slab of length tau_n; 0: no bound
  double supg_tau_factor = 1.;
  /// crosswind diffusion eps_cw,K = crosswind0 max(0, |b| h_cw,K / 2 - eps) across b
  /// (h_cw,K: the length of K across b at its centre); 0 turns it off
  double crosswind0 = 0.;
  /// linear: eps_cw,K as above on every cell; residual: times a factor s_K in [0, 1] set
  /// per cell from a previous solution (Space::set_crosswind_scale, crosswind_scale.h)
  CrosswindForm crosswind_form = CrosswindForm::linear;
  /// residual form: the factor is min(1, |R| / (|b| |grad u|))^crosswind_exponent
  double crosswind_exponent = 1.;
  /// Bound delta_K <= h_min,K^2 / (eps q^4) (h_min,K the shortest distance of two
  /// vertices of K, q the degree): keeps the SUPG term's eps Lap part below the
  /// diffusion (the inverse estimate |Lap v|_K <= q^2/h_min,K |grad v|_K), which on thin
  /// cells of a high degree it otherwise is not. Off for the primal.
  bool inverse_bound = false;
};
} // namespace anisodwr
