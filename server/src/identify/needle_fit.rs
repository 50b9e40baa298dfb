//! Needle force distribution from an insertion experiment: nodal forces f = K u along the shaft and the fitted friction per length and tip peak.
