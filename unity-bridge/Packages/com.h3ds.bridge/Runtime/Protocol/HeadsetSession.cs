// The headset's side of the protocol, independent of Unity: hello -> pair (token, or resume key after
// a drop) -> paired; numbering, acks and resending through the Outbox; reconnecting with back-off;
// answering pings and acking scene pushes. Poll() is called from one thread (Unity's Update); it
// reports what arrived through IHeadsetHandler on that thread.
using System;
using System.Collections.Generic;

namespace H3ds.Bridge.Protocol
{
    public interface IHeadsetHandler
    {
        void OnPaired(Paired paired);
        void OnScenePush(ScenePush push);
        /// <summary>An error from the studio, or a refused message of ours; fatal ones end the pairing.</summary>
        void OnStudioError(ErrorMessage error);
        void OnDisconnected(string reason);
    }

    public enum SessionState { Idle, Connecting, AwaitingHello, AwaitingPaired, Paired, Refused, Ended }

    public sealed class HeadsetSession : IDisposable
    {
        readonly Uri _uri;
        readonly IHeadsetHandler _handler;
        readonly Func<double> _clock;
        readonly Hello _hello;
        readonly Outbox _outbox;
        WebSocketLink _link;
        string _token, _resumeKey;
        double _retryAt, _backoff = 0.5;
        const double MaxBackoff = 5.0;

        public SessionState State { get; private set; }
        public string LastProblem { get; private set; }
        public Outbox Outbox { get { return _outbox; } }
        public long MaxMessageBytes { get; private set; }

        /// <param name="clock">Unix seconds (the envelope's ts and the reconnect timer).</param>
        public HeadsetSession(Uri uri, string session, Hello hello, IHeadsetHandler handler, Func<double> clock)
        {
            _uri = uri;
            _hello = hello;
            _handler = handler;
            _clock = clock;
            _outbox = new Outbox(session, clock);
            MaxMessageBytes = 65536;
        }

        /// <summary>Pairs with the 6-digit token shown in the studio (also after a wrong one was refused).</summary>
        public void PairWith(string token)
        {
            _token = token;
            _resumeKey = null;
            if (State == SessionState.Refused || State == SessionState.Idle) { State = SessionState.Idle; _retryAt = 0; }
        }

        /// <summary>Sends a message once paired; ones the studio acks are kept (and resent) until acked,
        /// others (a ping) are not sent while unpaired, since the studio refuses anything before pairing.</summary>
        public Envelope Send(IBody body)
        {
            var env = _outbox.Next(body);
            if (State == SessionState.Paired) Write(env);
            return env;
        }

        void Write(Envelope env)
        {
            if (_link != null && _link.IsOpen) _link.Send(env.ToJson());
        }

        /// <summary>Drives the connection: reconnects when due and handles every message that arrived.</summary>
        public void Poll()
        {
            if (State == SessionState.Refused || State == SessionState.Ended) return;
            if (State == SessionState.Idle)
            {
                if (_token == null && _resumeKey == null) return;
                if (_clock() >= _retryAt) Connect();
                return;
            }
            if (_link == null) return;
            if (State == SessionState.Connecting)
            {
                if (_link.IsOpen)
                {
                    Write(_outbox.Next(_hello));
                    State = SessionState.AwaitingHello;
                }
                else if (_link.CloseReason != null) Drop(_link.CloseReason);
                return;
            }
            string text;
            while (_link != null && _link.TryReceive(out text)) Handle(text);
            if (_link != null && !_link.IsOpen) Drop(_link.CloseReason);
        }

        void Connect()
        {
            State = SessionState.Connecting;
            _link = new WebSocketLink();
            _ = _link.ConnectAsync(_uri, TimeSpan.FromSeconds(5));  // failures show as CloseReason
        }

        void Drop(string reason)
        {
            LastProblem = reason;
            if (_link != null) { _link.Dispose(); _link = null; }
            if (State == SessionState.Refused || State == SessionState.Ended) return;
            State = SessionState.Idle;
            _retryAt = _clock() + _backoff;
            _backoff = Math.Min(MaxBackoff, _backoff * 2);
            _handler.OnDisconnected(reason);
        }

        /// <summary>Drops the connection as a network failure would (for tests and the in-headset debug menu).</summary>
        public void SimulateDrop() { if (_link != null) _link.Dispose(); }

        void Handle(string text)
        {
            Envelope env;
            try { env = Envelope.FromJson(text); }
            catch (ProtocolException e)
            {
                LastProblem = "ignored a message from the studio: " + e.Message;
                return;
            }
            try { Dispatch(env); }
            catch (ProtocolException e)
            {
                LastProblem = "ignored a " + env.Type + " from the studio: " + e.Message;
                if (env.Type == MessageTypes.ScenePush)
                    Send(new SceneFailed { Push = env.Body.ContainsKey("push") ? env.Body["push"] as string ?? env.Id : env.Id, Reason = e.Message });
            }
        }

        void Dispatch(Envelope env)
        {
            switch (env.Type)
            {
                case MessageTypes.Hello:
                    var studio = Hello.FromBody(env.Body);
                    if (studio.MaxMessageBytes.HasValue) MaxMessageBytes = studio.MaxMessageBytes.Value;
                    Write(_outbox.Next(_resumeKey != null ? new Pair { ResumeKey = _resumeKey } : new Pair { Token = _token }));
                    State = SessionState.AwaitingPaired;
                    break;
                case MessageTypes.Paired:
                    var paired = Paired.FromBody(env.Body);
                    _resumeKey = paired.ResumeKey;
                    _token = null;
                    _backoff = 0.5;
                    _outbox.StoredUpTo(paired.LastSeq);
                    State = SessionState.Paired;
                    foreach (var pending in _outbox.Unacked()) Write(pending);
                    _handler.OnPaired(paired);
                    break;
                case MessageTypes.Ack:
                    _outbox.Acknowledge(Ack.FromBody(env.Body).Seq);
                    break;
                case MessageTypes.ScenePush:
                    var push = ScenePush.FromBody(env.Body);
                    Write(_outbox.Next(new Ack { Of = env.Id, Seq = env.Seq }));
                    _handler.OnScenePush(push);
                    break;
                case MessageTypes.Ping:
                    Write(_outbox.Next(new Pong { PingId = env.Id }));
                    break;
                case MessageTypes.Pong:
                    break;
                case MessageTypes.Error:
                    var error = ErrorMessage.FromBody(env.Body);
                    if (error.Fatal)
                    {
                        // A refused token needs a new one from the studio; a lost resume key a new pairing.
                        State = SessionState.Refused;
                        _resumeKey = null;
                        LastProblem = error.Code + ": " + error.Message;
                        _link.Dispose();  // the studio closes it too
                        _link = null;
                    }
                    _handler.OnStudioError(error);
                    break;
                case MessageTypes.SessionEnd:
                    State = SessionState.Ended;
                    _resumeKey = null;
                    if (_link != null) { _link.Close("session end"); _link.Dispose(); _link = null; }
                    _handler.OnDisconnected("the studio ended the session: " + Fields.OptString(env.Body, "reason"));
                    break;
                default:
                    LastProblem = "ignored a message of unknown type '" + env.Type + "'";
                    break;
            }
        }

        /// <summary>Ends the session: tells the studio (best effort) and closes.</summary>
        public void End(string reason)
        {
            if (_link != null && State == SessionState.Paired) Write(_outbox.Next(new SessionEnd { Reason = reason }));
            State = SessionState.Ended;
            if (_link != null) { _link.Close(reason); _link.Dispose(); _link = null; }
        }

        public void Dispose() { if (_link != null) _link.Dispose(); }
    }
}
