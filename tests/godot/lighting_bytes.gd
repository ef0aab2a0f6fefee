# IsoluxLighting (the GDNative library) inside Godot: opens $ISOLUX_LEVEL (a
# scene JSON or a .tmx), optionally adds a light, renders the default view's
# $ISOLUX_LAYER ("light" or "final") and writes the raw RGBA bytes to
# $ISOLUX_BYTES_OUT; a refusal must come back as false plus a message.
extends SceneTree


func _init():
	var lighting = load("res://addons/isolux/isolux_lighting.gdns").new()
	if lighting.api_version() != 2:
		printerr("api version ", lighting.api_version())
		quit(1)
		return
	if lighting.open_scene("/nonexistent/level.json") or lighting.last_error().find("level.json") < 0:
		printerr("a missing level is not refused by name: ", lighting.last_error())
		quit(1)
		return
	var level = OS.get_environment("ISOLUX_LEVEL")
	var ok = lighting.open_tmx(level) if level.ends_with(".tmx") else lighting.open_scene(level)
	if not ok:
		printerr("open: ", lighting.last_error())
		quit(1)
		return
	if lighting.set_param("ray_skip", "-1"):
		printerr("ray_skip -1 accepted")
		quit(1)
		return
	var v = lighting.default_view()
	var bytes = lighting.render(int(v.position.x), int(v.position.y), int(v.size.x), int(v.size.y), 0,
		OS.get_environment("ISOLUX_LAYER"))
	if bytes.size() != int(v.size.x * v.size.y * 4):
		printerr("render: ", lighting.last_error())
		quit(1)
		return
	var f = File.new()
	f.open(OS.get_environment("ISOLUX_BYTES_OUT"), File.WRITE)
	f.store_buffer(bytes)
	f.close()
	print("rendered %s: %dx%d" % [level, v.size.x, v.size.y])
	quit(0)
