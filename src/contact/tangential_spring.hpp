// the tangential state a Model P contact carries from step to step; it lives with the contacts
// (which store it) and the friction law updates it
#pragma once

namespace gs {

/// the Cundall–Strack state of one contact between steps (P.35)
struct TangentialSpring {
  double spring = 0.0;  ///< F*∥ of the previous step, N
  double v_prev = 0.0;  ///< v∥ of the previous step, m/s
};

}  // namespace gs
