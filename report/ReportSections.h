#pragma once
// The report's sections (report/Report.h), each drawn at the document's cursor; reportPdf puts
// them in order. For the report's own files only.

#include <string>

#include "report/Report.h"
#include "report/ReportDocument.h"

namespace candela {
struct PhotometricData;
}

namespace candela::report_detail {

/// Per room: its data table and its plan seen from above (report/ReportRooms.cpp).
void roomSections(Pdf& pdf, const ReportInput& in);
/// The luminaires' input power per floor area and per 100 lx (report/ReportRooms.cpp).
void powerDensitySection(Pdf& pdf, const ReportInput& in);
/// One datasheet per distinct photometry: figures, polar diagram, UGR table
/// (report/ReportDatasheet.cpp).
void datasheetSections(Pdf& pdf, const ReportInput& in);
/// Every calculation surface and the points (report/ReportSurfaces.cpp).
void surfacesSection(Pdf& pdf, const ReportInput& in);

/// "Em >= 500 lx, U0 >= 0.60", or "no requirement".
std::string requirementText(const Requirement& r, bool cylindrical, const char* unit);

/// The factor from a photometry's candela to cd/klm: per 1000 lm of its lamps' flux, or of the
/// luminaire's own for absolute photometry (no lamp flux stated).
double perKilolumen(const PhotometricData& d, double scale);

}  // namespace candela::report_detail
