// A console program over the package's pure C# protocol layer (H3ds.Bridge.Protocol.dll), run under
// mono by tests/test_unity_package.py. It is a test driver, not a headset:
//   samples DIR                       write one message of every type the headset sends (DIR/<name>.json)
//   parse FILE...                     read messages (e.g. the studio's or the simulator's) and print what was understood
//   session URL TOKEN SESSION EVENTS DROP_AT
//                                     pair with a studio endpoint, take one scene_push, report its plan steps
//                                     as done (no AI2-THOR here), send EVENTS glove events, drop the connection
//                                     once after DROP_AT of them, reconnect, and wait until every message is acked
using System;
using System.Collections.Generic;
using System.IO;
using System.Threading;
using H3ds.Bridge.Protocol;

static class ProtocolCheck
{
    static double Now() { return (DateTime.UtcNow - new DateTime(1970, 1, 1, 0, 0, 0, DateTimeKind.Utc)).TotalSeconds; }

    static int Main(string[] args)
    {
        try
        {
            if (args.Length >= 2 && args[0] == "samples") return Samples(args[1]);
            if (args.Length >= 2 && args[0] == "parse") return Parse(args);
            if (args.Length == 6 && args[0] == "session") return Session(args[1], args[2], args[3], int.Parse(args[4]), int.Parse(args[5]));
        }
        catch (ProtocolException e) { Console.Error.WriteLine("protocol error: " + e.Message); return 2; }
        Console.Error.WriteLine("usage: ProtocolCheck samples DIR | parse FILE... | session URL TOKEN SESSION EVENTS DROP_AT");
        return 64;
    }

    static HapticProfile ColdProfile()
    {
        return HapticProfile.FromBody((Dictionary<string, object>)Json.Parse(
            "{\"object_id\":\"Fridge|1\",\"scene_object_id\":\"fridge_0\",\"object_type\":\"Fridge\",\"haptic_class\":\"cold\"," +
            "\"touch\":{\"intensities\":[20,40,40,30,20,0],\"duration_ms\":120}," +
            "\"grasp\":{\"intensities\":[60,80,80,70,50,30],\"duration_ms\":200,\"pulses\":2,\"gap_ms\":80}," +
            "\"colour\":{\"start\":[0,0,0],\"end\":[0,0.3,1],\"duration_ms\":1500,\"name\":\"cooling\"},\"why\":\"isColdSource\"}"));
    }

    static int Samples(string dir)
    {
        Directory.CreateDirectory(dir);
        var outbox = new Outbox("3f0c8a52-5d7e-4c1b-9a57-0c5b1f6f2a10", Now);
        string push = "9b1d7c1e-7f0a-4f43-8a4e-6c1d2b3a4f50";
        var profile = ColdProfile();
        var bodies = new List<KeyValuePair<string, IBody>>
        {
            Pair("hello", new Hello { Device = "Meta Quest 3", AppVersion = "0.1.0", Capabilities = new List<string> { "ai2thor", "hand-tracking", "bhaptics" }, Gloves = new GloveState { Left = true, Right = false } }),
            Pair("pair_token", new Pair { Token = "042917" }),
            Pair("pair_resume", new Pair { ResumeKey = "k3Vb2-9xQe_7hTzL0aP4" }),
            Pair("scene_loaded", new SceneLoaded { Push = push, LoadMs = 1834.5, Objects = 23 }),
            Pair("scene_failed", new SceneFailed { Push = push, Reason = "house metadata.schema is '0.9'; AI2-THOR's CreateHouse accepts only '1.0.0'" }),
            Pair("plan_step_result", new PlanStepResult { Push = push, Index = 2, Of = 7, Action = "OpenObject", Ok = true, Message = "open the fridge" }),
            Pair("plan_step_result_failed", new PlanStepResult { Push = push, Index = 3, Of = 7, Action = "PickupObject", Ok = false }),
            Pair("glove_event_hover", GloveRules.Event(push, 3.25, "Fridge|1", "Fridge", "hover", "right", GloveRules.FingerNames(2), profile, GloveRules.Neutral)),
            Pair("glove_event_select", GloveRules.Event(push, 4.0, "Fridge|1", "Fridge", "select", "left", GloveRules.FingerNames(31), profile,
                GloveRules.ColourAfter("select", profile, 0, null))),
            Pair("glove_event_unselect", GloveRules.Event(push, 6.0, "Fridge|1", "Fridge", "unselect", "left", GloveRules.FingerNames(3), profile,
                GloveRules.ColourAfter("unselect", profile, 2000, null))),
            Pair("user_decision", new UserDecision { Push = push, Decision = "accept", Comment = "the bread is cold" }),
            Pair("ping", new Ping()),
            Pair("pong", new Pong { PingId = "ping-17" }),
            Pair("ack", new Ack { Of = push, Seq = 12 }),
            Pair("session_end", new SessionEnd { Reason = "headset app closed" }),
        };
        foreach (var kv in bodies) File.WriteAllText(Path.Combine(dir, kv.Key + ".json"), outbox.Next(kv.Value).ToJson());
        Console.WriteLine(Json.Write(new Dictionary<string, object> { { "written", (long)bodies.Count }, { "pending_acks", (long)outbox.Pending } }));
        return 0;
    }

    static KeyValuePair<string, IBody> Pair(string name, IBody body) { return new KeyValuePair<string, IBody>(name, body); }

    static int Parse(string[] args)
    {
        for (int i = 1; i < args.Length; i++)
        {
            var env = Envelope.FromJson(File.ReadAllText(args[i]));
            var summary = new Dictionary<string, object> { { "file", Path.GetFileName(args[i]) }, { "type", env.Type }, { "seq", env.Seq }, { "id", env.Id } };
            switch (env.Type)
            {
                case MessageTypes.ScenePush:
                    var push = ScenePush.FromBody(env.Body);
                    object meta;
                    push.House.TryGetValue("metadata", out meta);
                    var steps = new List<object>();
                    if (push.Plan != null) foreach (var s in push.Plan.Steps) steps.Add(Json.Write(s.Action));
                    summary["push"] = push.Push;
                    summary["house_schema"] = meta is Dictionary<string, object> ? ((Dictionary<string, object>)meta)["schema"] : null;
                    summary["house_json"] = push.HouseJson;
                    summary["vr_best"] = push.VrBest == null ? null : new List<object> { push.VrBest.X, push.VrBest.Z, push.VrBest.Rotation };
                    summary["haptic_objects"] = new List<object>(push.HapticProfiles.Keys);
                    summary["steps"] = steps;
                    break;
                case MessageTypes.Hello: summary["device"] = Hello.FromBody(env.Body).Device; break;
                case MessageTypes.Paired: summary["last_seq"] = Paired.FromBody(env.Body).LastSeq; break;
                case MessageTypes.Ack: summary["of"] = Ack.FromBody(env.Body).Of; break;
                case MessageTypes.Error: summary["code"] = ErrorMessage.FromBody(env.Body).Code; break;
            }
            Console.WriteLine(Json.Write(summary));
        }
        return 0;
    }

    sealed class Driver : IHeadsetHandler
    {
        public HeadsetSession Session;
        public int Paired, Disconnects;
        public ScenePush Push;
        public string Error;
        public void OnPaired(Paired paired) { Paired++; }
        public void OnScenePush(ScenePush push)
        {
            Push = push;
            Session.Send(new SceneLoaded { Push = push.Push, LoadMs = 1, Objects = push.HapticProfiles.Count });
            int n = push.Plan == null ? 0 : push.Plan.Steps.Count;
            for (int i = 0; i < n; i++)
                Session.Send(new PlanStepResult { Push = push.Push, Index = i, Of = n, Action = push.Plan.Steps[i].ActionName, Ok = true, Message = "not executed: protocol check" });
        }
        public void OnStudioError(ErrorMessage error) { Error = error.Code + ": " + error.Message; }
        public void OnDisconnected(string reason) { Disconnects++; }
    }

    static int Session(string url, string token, string sessionId, int events, int dropAt)
    {
        var driver = new Driver();
        var hello = new Hello { Device = "ProtocolCheck (mono test driver)", AppVersion = "0.1.0", Capabilities = new List<string> { "protocol-check" }, Gloves = new GloveState { Left = true, Right = true } };
        var session = new HeadsetSession(new Uri(url), sessionId, hello, driver, Now);
        driver.Session = session;
        session.PairWith(token);
        var deadline = DateTime.UtcNow.AddSeconds(60);
        int sent = 0;
        bool dropped = false;
        var watch = new System.Diagnostics.Stopwatch();
        string[] kinds = { "hover", "select", "unselect", "unhover" };
        while (DateTime.UtcNow < deadline && session.State != SessionState.Refused)
        {
            session.Poll();
            if (driver.Push != null && sent < events)
            {
                if (!watch.IsRunning) watch.Start();
                var ids = new List<string>(driver.Push.HapticProfiles.Keys);
                for (int k = 0; k < 50 && sent < events; k++, sent++)
                {
                    var profile = driver.Push.HapticProfiles[ids[sent % ids.Count]];
                    string kind = kinds[sent % 4];
                    session.Send(GloveRules.Event(driver.Push.Push, sent * 0.01, profile.ObjectId, profile.ObjectType, kind, sent % 2 == 0 ? "left" : "right",
                        GloveRules.FingerNames(sent % 32), profile, GloveRules.ColourAfter(kind, profile, 500, null)));
                    if (!dropped && sent + 1 >= dropAt) { session.SimulateDrop(); dropped = true; }
                }
            }
            if (driver.Push != null && sent >= events && session.Outbox.Pending == 0) break;
            Thread.Sleep(1);
        }
        int pending = session.Outbox.Pending;
        var state = session.State;
        session.End("protocol check done");
        Console.WriteLine(Json.Write(new Dictionary<string, object>
        {
            { "paired", (long)driver.Paired }, { "disconnects", (long)driver.Disconnects }, { "push", driver.Push == null ? null : driver.Push.Push },
            { "events_sent", (long)sent }, { "pending", (long)pending }, { "dropped_from_buffer", session.Outbox.Dropped },
            { "error", driver.Error }, { "seconds_to_all_acked", watch.Elapsed.TotalSeconds }, { "last_problem", session.LastProblem }, { "state", state.ToString() },
        }));
        return pending == 0 && driver.Push != null ? 0 : 1;
    }
}
