# Imports $ISOLUX_TMX (exported with --normal-maps) and draws it in the
# windowed godot3 over the world rectangle $ISOLUX_VIEW ("x,y,w,h"), the
# CanvasModulate taken out and the lights casting no shadows, four times
# into $ISOLUX_OUT_PREFIX + "<name>.png": `mask` (the overlays alone, the
# background transparent), `dark` (no light), `normals` (the lights over the
# sprites' normal maps) and `flat` (the same lights, the normal maps taken
# off), the normal maps imported in the frame $ISOLUX_NORMALS names (the
# importer's normal_frame: ground, screen or as_written).
extends SceneTree

var frames := 0
var stage := 0
var view := Rect2()
var level: Node2D = null
const STAGES := ["mask", "dark", "normals", "flat"]


func _init():
	var importer = load("res://addons/isolux/tmx_importer.gd").new()
	importer.normal_frame = OS.get_environment("ISOLUX_NORMALS")
	level = importer.import_tmx(OS.get_environment("ISOLUX_TMX"))
	if level == null:
		printerr("import: ", importer.error)
		quit(1)
		return
	var with_normal = 0
	for s in level.get_node("Overlays").get_children():
		with_normal += 1 if s.normal_map != null else 0
	print("overlays with a normal map: %d of %d" % [with_normal, level.get_node("Overlays").get_child_count()])
	for l in level.get_node("Lights").get_children():
		l.shadow_enabled = false
	view = preload("res://view.gd").show(self, level)
	_arrange()


func _arrange():
	var name = STAGES[stage]
	level.get_node("Floors").visible = name != "mask"
	level.get_node("Lights").visible = name == "normals" or name == "flat"
	if name == "flat":
		for s in level.get_node("Overlays").get_children():
			s.normal_map = null


func _idle(_delta):
	if level == null:
		return false
	frames += 1
	if frames < 4:
		return false
	var img: Image = get_root().get_texture().get_data()
	img.flip_y()
	img.save_png(OS.get_environment("ISOLUX_OUT_PREFIX") + STAGES[stage] + ".png")
	stage += 1
	frames = 0
	if stage == STAGES.size():
		print("drew %d pictures of %dx%d" % [STAGES.size(), img.get_width(), img.get_height()])
		quit(0)
		return false
	_arrange()
	return false
