// The DVL translation of python/unexmin/translators/dvl.py (dvl_to_water_track), in C++ so that it keeps up in
// lockstep: unexmin/Dvl (one simulated ping) -> dvl_nortek/DvlBottomWaterTrack (the UX-1 driver's bottom-track
// record). Same conventions, field by field (docs/translators.md); test/pytest/test_cpp_translations.py compares
// the two on the simulator's own messages.
#pragma once

#include <dvl_nortek/DvlBottomWaterTrack.h>
#include <unexmin/Dvl.h>

namespace unexmin {
namespace ros_layer {

/// Header kept; pressure [Pa] -> [dbar]; ranges vertical; times from the slant ranges and the sound speed.
dvl_nortek::DvlBottomWaterTrack waterTrack(const unexmin::Dvl& dvl);

}  // namespace ros_layer
}  // namespace unexmin
