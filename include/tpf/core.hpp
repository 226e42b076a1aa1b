// Everything a controller needs from tpf::core, in one include.
#pragma once

#include "tpf/common/error.hpp"
#include "tpf/common/types.hpp"
#include "tpf/dynamics/coriolis.hpp"
#include "tpf/dynamics/energy.hpp"
#include "tpf/dynamics/forward_dynamics.hpp"
#include "tpf/dynamics/mass_matrix.hpp"
#include "tpf/dynamics/regressor.hpp"
#include "tpf/dynamics/rnea.hpp"
#include "tpf/kinematics/contact_frame.hpp"
#include "tpf/kinematics/forward_kinematics.hpp"
#include "tpf/kinematics/point_jacobian.hpp"
#include "tpf/model/data.hpp"
#include "tpf/model/load_robot.hpp"
#include "tpf/model/model.hpp"
#include "tpf/skin/pad_layout.hpp"
