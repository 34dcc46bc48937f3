#pragma once
// Zemax OpticStudio sequential lens files (.zmx), as lens vendors publish one per part.
// optics/lenses/README.md lists what is read and what is refused; in short:
//   read     UNIT (MM, CM, IN, METER), NAME, MODE SEQ, GCAT, ENPD, FNUM, WAVM/WAVL, PWAV, and per
//            SURF: TYPE STANDARD or EVENASPH, CURV (curvature), CONI, PARM (EVENASPH terms on
//            r^2, r^4, ...), DISZ (INFINITY allowed), GLAS (a catalogue name, or the model form
//            n_d/V_d when the name is found in no catalogue, with a warning), DIAM (semi-diameter),
//            STOP, and coordinate breaks that neither decentre nor tilt;
//   refused  any other surface TYPE (toroids, gratings, ...), GLAS MIRROR, a coordinate break
//            with a decentre or tilt, non-sequential mode or objects, and apertures inim cannot
//            model (rectangular, elliptical, obscurations) -- each with the surface number,
//            the line and the keyword;
//   ignored  display, tolerance, coating, solve and optimisation data (they do not change the
//            lens as built).
// The object surface (SURF 0) and the image surface (the last) are not lens surfaces: the last
// lens surface's DISZ becomes the sensor distance. A STOP on a curved or glass surface becomes
// a flat stop in front of it (at the surface's vertex, or at its edge when the surface bows
// toward the object), since inim's stop is a flat opening.
#include <string>

#include "camera/lens_loader.h"

namespace inim {

// Parses the bytes of a .zmx file (UTF-16 with or without its byte-order mark, UTF-8 or ASCII;
// CRLF or LF); `file` names it in messages. The result is validated; what the file gives that
// inim reads only approximately is in the lens's design().warnings.
LensSystem parseZmxLens(const std::string& bytes, const std::string& file, const LensLoadOptions& opt = {});

}  // namespace inim
