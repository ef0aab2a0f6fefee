# Imports $ISOLUX_TMX with the add-on's importer, saves the scene to
# $ISOLUX_SCENE_OUT and writes where every node landed to $ISOLUX_NODES_OUT
# (JSON, world pixels). With $ISOLUX_DRAW_OUT (the windowed godot3, under a
# display) it also draws the level with its lights and CanvasModulate off over
# the world rectangle $ISOLUX_VIEW ("x,y,w,h") and saves that as a PNG.
extends SceneTree

var frames := 0
var view := Rect2()


func _init():
	var importer = load("res://addons/isolux/tmx_importer.gd").new()
	var level = importer.import_tmx(OS.get_environment("ISOLUX_TMX"))
	if level == null:
		printerr("import: ", importer.error)
		quit(1)
		return
	var nodes = {"lights": [], "occluders": [], "sprites": [], "floors": {}}
	for l in level.get_node("Lights").get_children():
		nodes["lights"].push_back({"name": l.name, "x": l.position.x, "y": l.position.y, "color": l.color.to_html(false),
			"energy": l.energy, "area": [l.get_meta("isolux_area").x, l.get_meta("isolux_area").y],
			"drawn": [l.texture.get_width() * l.texture_scale * l.scale.x / 2.0,
				l.texture.get_height() * l.texture_scale * l.scale.y / 2.0]})
	for o in level.get_node("Occluders").get_children():
		var pts = []
		for p in o.occluder.polygon:
			pts.push_back([o.position.x + p.x, o.position.y + p.y])
		nodes["occluders"].push_back(pts)
	for s in level.get_node("Overlays").get_children():
		nodes["sprites"].push_back([s.position.x, s.position.y, s.region_rect.size.x, s.region_rect.size.y])
	var tm: TileMap = level.get_node("Floors")
	nodes["floors"] = {"cells": tm.get_used_cells().size(), "top_corner_0_0": [tm.position.x, tm.position.y]}
	nodes["ambient"] = level.get_node("Ambient").color.r
	var f = File.new()
	f.open(OS.get_environment("ISOLUX_NODES_OUT"), File.WRITE)
	f.store_string(to_json(nodes))
	f.close()
	var packed = PackedScene.new()
	if packed.pack(level) != OK or ResourceSaver.save(OS.get_environment("ISOLUX_SCENE_OUT"), packed) != OK:
		printerr("import: could not save the scene")
		quit(1)
		return
	print("imported: %d sprites, %d lights, %d occluders, %d floor cells" % [nodes["sprites"].size(),
		nodes["lights"].size(), nodes["occluders"].size(), nodes["floors"]["cells"]])
	if OS.get_environment("ISOLUX_DRAW_OUT") == "":
		level.free()
		quit(0)
		return
	level.get_node("Lights").visible = false
	view = preload("res://view.gd").show(self, level)


func _idle(_delta):
	if view.size == Vector2.ZERO:
		return false
	frames += 1
	if frames < 4:
		return false
	var img: Image = get_root().get_texture().get_data()
	img.flip_y()
	img.save_png(OS.get_environment("ISOLUX_DRAW_OUT"))
	print("drew %dx%d" % [img.get_width(), img.get_height()])
	quit(0)
	return false
