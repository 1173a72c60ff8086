#include "methods/mboit/mboit_settings.hpp"

#include "starnt/error.hpp"

namespace starnt::mboit {

const MomentSetting& momentSetting(MomentKind kind) {
    static const MomentSetting settings[] = {
        {MomentKind::Power4, "4", false, 4, 2, 5e-7f, {0.0f, 0.375f, 0.0f, 0.375f, 0.0f, 0.0f}},
        {MomentKind::Power6, "6", false, 6, 3, 5e-6f, {0.0f, 0.48f, 0.0f, 0.451f, 0.0f, 0.45f}},
        {MomentKind::Trig2, "t2", true, 2, 2, 4e-7f, {}},
        {MomentKind::Trig3, "t3", true, 3, 3, 8e-7f, {}},
    };
    return settings[int(kind)];
}

MomentKind parseMomentKind(const std::string& text) {
    for (MomentKind k : {MomentKind::Power4, MomentKind::Power6, MomentKind::Trig2, MomentKind::Trig3}) {
        if (text == momentSetting(k).name) return k;
    }
    throw Error("MethodOptions::mboit.moments (--mboit-moments) '" + text + "': expected 4, 6, t2 or t3 (power moments 4 or 6, trigonometric 2 or 3)");
}

}  // namespace starnt::mboit
