# Sourced by the GUI checks (render_e2e.sh, gui_e2e.sh): where things are in the GUI of MeshLab
# 2022.02 and 2025.07, as gui_shot.sh steps. hosts_gui_menus VERSION sets
#   GUI_VIEW          the 3D view above its info box (ImageMagick crop WxH+X+Y)
#   GUI_LOG           the log pane (crop)
#   GUI_FIRST_EYE     the eye of the first layer in the layer dialog (a click hides that layer)
#   GUI_SPLAT_STEPS   Render > Shaders > Ellipse Splatting, then its settings panel moved off the view
#   GUI_FILTER_STEPS  Filters > Point Set > Gaussian Sphere Feature-Sensitive Resampling, Apply
#                     (Return: the dialog gives Apply the focus), the wait for MeshLab's log line
#                     "Applied filter", then the dialog moved off the view
# Taken from screenshots at the Xvfb screen 1280x1024 (lib.sh): each menu, a point along the
# first row of its submenu (so that the submenu stays open on the way down), the entry.
# 2025.07's MINI build has only Shaders in the Render menu, so that submenu opens further left,
# and only the project's two filters in Filters > Point Set (2022.02: 13 filters, sorted by
# name), so the resampling is its first entry; its view is narrower and taller.
hosts_gui_menus() {
  local render=170,9 shaders=200,31 along entry view log eye filters=116,9 pointset=150,355 pointset_along=520,355 filter
  case "$1" in
    2022.02) along=520,31 entry=560,54 view=449x510+1+70 log=380x75+466+588 filter=600,447 eye=490,111 ;;
    2025.07) along=300,31 entry=340,54 view=408x541+1+70 log=410x64+430+594 filter=600,355 eye=449,111 ;;
    *) echo "hosts_gui_menus: unknown MeshLab host '$1' (2022.02 or 2025.07)" >&2; return 2 ;;
  esac
  GUI_VIEW=$view GUI_LOG=$log GUI_FIRST_EYE=$eye
  GUI_SPLAT_STEPS=(--click "$render" --click "$shaders" --hover "$along" --click "$entry"
    --xdotool "search --name ^Ellipse.Splatting$ windowmove %@ 900 120")
  local dialog="^Gaussian Sphere Feature-Sensitive Resampling$"
  GUI_FILTER_STEPS=(--click "$filters" --click "$pointset" --hover "$pointset_along" --click "$filter"
    --window "$dialog" --xdotool "key Return" --wait-log "Applied filter:? Gaussian Sphere Feature-Sensitive Resampling"
    --xdotool "search --name ${dialog// /.} windowmove %@ 860 60")
}
