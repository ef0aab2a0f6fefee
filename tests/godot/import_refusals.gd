# The add-on's importer against hostile maps: each case of $ISOLUX_CASES
# (JSON: [{"tmx", "want", "lights"}]) must come back as null with `error`
# holding "want", or, when "want" is "", import with that many Light2D.
# Godot must not crash, hang or print a script error on any of them.
extends SceneTree


func _init():
	var f = File.new()
	f.open(OS.get_environment("ISOLUX_CASES"), File.READ)
	var cases = parse_json(f.get_as_text())
	f.close()
	var failed = 0
	for c in cases:
		var importer = load("res://addons/isolux/tmx_importer.gd").new()
		var level = importer.import_tmx(c["tmx"])
		var ok = false
		if c["want"] == "":
			ok = level != null and level.get_node("Lights").get_child_count() == int(c["lights"])
		else:
			ok = level == null and importer.error.find(c["want"]) >= 0
		if level != null:
			level.free()
		print("%s %s: %s" % ["ok" if ok else "FAIL", c["tmx"].get_file(), importer.error])
		if not ok:
			failed += 1
	print("refusals: %d of %d cases as expected" % [cases.size() - failed, cases.size()])
	quit(1 if failed > 0 else 0)
