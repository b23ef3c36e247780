# A .surfel file without surfels loads as an empty layer and saves back unchanged.
source "$E2E_COMMON"
"$SURFEL_FIXTURE" empty.surfel 0
"$RUN_MESHLABSERVER" -i empty.surfel -o out.surfel
cmp empty.surfel out.surfel
"$SURFEL_CHECK" out.surfel --count 0
