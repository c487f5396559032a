"""The compliant Painleve rod: analytic results of Hogan & Kristiansen and IWC experiments on the FMU."""
