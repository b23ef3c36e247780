# Loading and saving a .surfel file through meshlabserver, with no filter and no save mask,
# keeps every attribute bit for bit (the plugin writes them whatever the mask says).
source "$E2E_COMMON"
"$SURFEL_FIXTURE" in.surfel 300
"$RUN_MESHLABSERVER" -i in.surfel -o out.surfel
cmp in.surfel out.surfel
"$SURFEL_CHECK" out.surfel --count 300 --require-ellipses --quality-sum 1491
