# Doxygen input filter (docs/Doxyfile.in): inside /// comments, "#V" (an array size, libigl style)
# becomes "\#V", which doxygen prints as "#V" instead of taking it for a link to a member named V.
:again
s|(///.*[^\\])#([A-Za-z_])|\1\\#\2|
t again
