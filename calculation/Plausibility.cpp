#include "calculation/Plausibility.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "calculation/UgrTable.h"
#include "formats/Gldf.h"
#include "formats/Photometry.h"
#include "luminaires/photometric/PhotometricLuminaire.h"
#include "util/Error.h"
#include "util/TextEncoding.h"

namespace candela {

namespace {

template <typename... T>
std::string format(const char* f, T... values) {
    char line[512];
    std::snprintf(line, sizeof line, f, values...);
    return line;
}

/// "+406 %", "-12.5 %": how far `a` lies from `b`.
std::string deviation(double a, double b) {
    double d = 100.0 * (a / b - 1.0);
    return format(std::abs(d) >= 100.0 ? "%+.0f %%" : "%+.1f %%", d);
}

bool differ(double a, double b) {
    return a > 0.0 && b > 0.0 && std::abs(a / b - 1.0) > kRatedFluxTolerance;
}

}  // namespace

std::vector<std::string> plausibilityNotes(const std::string& name, const PhotometricData& d,
                                           const GldfLightEmitter* rated, bool withUgr) {
    std::vector<std::string> out;
    std::string shown = toValidUtf8(name);
    const char* n = shown.c_str();
    double table = d.fluxFromTable();
    bool relative = d.lampFlux > 0.0;
    // The flux Candela computes with, said once per line.
    std::string uses = format("Candela uses the table's %.5g lm", table);

    // A rated flux against the photometry. A fixed emitter rates the luminaire (the table's
    // flux); a changeable one rates its light source, which relative photometry was measured
    // with (its lamp flux) and absolute photometry already includes losses of.
    if (rated && rated->ratedFlux > 0.0) {
        if (!rated->fixed && relative) {
            if (differ(rated->ratedFlux, d.lampFlux))
                out.push_back(format(
                    "%s: the product rates its light source at %.5g lm, but the photometry was "
                    "measured with %.5g lm of lamps (%s); %s",
                    n, rated->ratedFlux, d.lampFlux,
                    deviation(rated->ratedFlux, d.lampFlux).c_str(), uses.c_str()));
        } else if (differ(rated->ratedFlux, table)) {
            out.push_back(
                format("%s: the product rates %.5g lm, but its intensity table holds "
                       "%.5g lm (%s); %s",
                       n, rated->ratedFlux, table, deviation(rated->ratedFlux, table).c_str(),
                       uses.c_str()));
        }
    }
    if (differ(d.statedFlux, table))
        out.push_back(format(
            "%s: the file states a luminous flux of %.5g lm, but its intensity table holds %.5g lm "
            "(%s); %s",
            n, d.statedFlux, table, deviation(d.statedFlux, table).c_str(), uses.c_str()));

    // The light output ratio: the declared one against the table's, and either above 100 %.
    if (relative) {
        double lor = table / d.lampFlux;
        if (d.declaresLightOutputRatio && d.lightOutputRatio > 0.0 &&
            std::abs(lor / d.lightOutputRatio - 1.0) > kLorTolerance)
            out.push_back(format(
                "%s: the file declares a light output ratio of %.4g %% but its table gives "
                "%.1f %% of the lamp flux (%.5g lm of %.5g lm); %s",
                n, 100.0 * d.lightOutputRatio, 100.0 * lor, table, d.lampFlux, uses.c_str()));
        else if (d.declaresLightOutputRatio && d.lightOutputRatio > 1.0 + kLorTolerance)
            out.push_back(
                format("%s: the file declares a light output ratio of %.4g %%: a "
                       "luminaire cannot emit more than its lamps; %s",
                       n, 100.0 * d.lightOutputRatio, uses.c_str()));
        else if (!d.declaresLightOutputRatio && lor > 1.0 + kLorTolerance)
            out.push_back(format(
                "%s: the table's flux is %.1f %% of the rated lamp flux (%.5g lm of %.5g lm): a "
                "luminaire cannot emit more than its lamps (the lamp lumens are wrong, or the "
                "photometry is absolute); %s",
                n, 100.0 * lor, table, d.lampFlux, uses.c_str()));
    }

    // Efficacy: the rated figures' own, and the table's flux over the power Candela shows.
    double power = rated && rated->ratedPower > 0.0 ? rated->ratedPower : d.inputWatts;
    if (rated && rated->ratedFlux > 0.0 && rated->ratedPower > 0.0 &&
        rated->ratedFlux / rated->ratedPower > kMaxPlausibleEfficacy)
        out.push_back(format(
            "%s: the product rates %.5g lm at %.4g W, %.1f lm/W, more than the %.0f lm/W white "
            "light reaches; %s (%.1f lm/W)",
            n, rated->ratedFlux, rated->ratedPower, rated->ratedFlux / rated->ratedPower,
            kMaxPlausibleEfficacy, uses.c_str(), table / rated->ratedPower));
    else if (power > 0.0 && table / power > kMaxPlausibleEfficacy)
        out.push_back(
            format("%s: the table's %.5g lm at the stated %.4g W is %.1f lm/W, more than "
                   "the %.0f lm/W white light reaches (the power or the flux is wrong); "
                   "%s",
                   n, table, power, table / power, kMaxPlausibleEfficacy, uses.c_str()));

    // The UGR reference: a value no real luminaire gives points at intensities in a wrong unit or
    // a wrong luminous area.
    if (withUgr) {
        try {
            UgrTable t = computeUgrTable(d);
            for (const UgrRoomResult& r : t.rooms) {
                if (r.size.x != 4 || r.size.y != 8) continue;
                for (double ugr : {r.crosswise[0], r.endwise[0]})
                    if (std::isfinite(ugr) && (ugr < kMinPlausibleUgr || ugr > kMaxPlausibleUgr)) {
                        out.push_back(format(
                            "%s: its UGR reference (CIE 190 table, room 4H x 8H, reflectances "
                            "70/50/20 %%) is %.1f, outside the %.0f-%.0f real luminaires give "
                            "(check the intensities' unit and the luminous dimensions); Candela "
                            "computes "
                            "glare from the table as it is",
                            n, ugr, kMinPlausibleUgr, kMaxPlausibleUgr));
                        break;
                    }
            }
        } catch (const InputError&) {
            // No luminous area (a point source): no UGR reference to judge.
        }
    }
    return out;
}

std::vector<std::string> plausibilityNotes(const PhotometricLuminaire& light, bool withUgr) {
    if (!light.data) return {};
    std::string name = std::filesystem::path(light.file).filename().string();
    return plausibilityNotes(name, *light.data, light.gldf ? light.gldfLightEmitter() : nullptr,
                             withUgr);
}

}  // namespace candela
